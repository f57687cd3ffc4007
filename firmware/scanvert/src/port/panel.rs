//! Shipping bands to a MIPI-DCS panel (ST7789, ILI9341 and the like)
//! over `embedded-hal` 1.0's blocking [`SpiDevice`] and a data/command
//! [`OutputPin`].
//!
//! Per band: CASET (0x2a) for the columns, RASET (0x2b) for the rows,
//! RAMWR (0x2c), then the pixels as big-endian RGB565 bytes, converted
//! through a caller-owned byte buffer in chunks (no allocation). A band
//! of words ([`PackedBand`](super::packed_band::PackedBand)) holds those
//! bytes already: [`Panel`] copies them into the buffer as they are.
//!
//! [`Panel`] blocks until the bytes are sent. [`AsyncPanel`] does the same
//! over `embedded-hal-async`'s [`SpiDevice`](embedded_hal_async::spi::SpiDevice),
//! so that with a DMA-driven SPI the band is sent while the next one is
//! drawn ([`FramePass::draw_async`](crate::frame::FramePass::draw_async)).
//!
//! Not done here: panel initialisation (reset, SLPOUT, COLMOD, MADCTL,
//! DISPON) is the application's or its panel driver's.

use embedded_graphics_core::pixelcolor::{raw::RawU16, Rgb565};
use embedded_graphics_core::prelude::RawData;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::SpiDevice;

use super::band::{AsyncBandTarget, BandTarget};
use super::packed_band::PackedBandTarget;

/// DCS column address set.
pub const CASET: u8 = 0x2a;
/// DCS row address set.
pub const RASET: u8 = 0x2b;
/// DCS memory write.
pub const RAMWR: u8 = 0x2c;

/// Why a band could not be shipped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum PanelError<S, P> {
    /// The SPI device failed.
    Spi(S),
    /// The data/command pin failed.
    Pin(P),
    /// The byte buffer holds fewer than 2 bytes, or the band's pixels are
    /// not `rows × width` for a whole width, or an address overflows `u16`.
    Shape,
}

impl<S: core::fmt::Debug, P: core::fmt::Debug> core::fmt::Display for PanelError<S, P> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            PanelError::Spi(e) => write!(f, "the panel's SPI device failed: {e:?}"),
            PanelError::Pin(e) => write!(f, "the panel's data/command pin failed: {e:?}"),
            PanelError::Shape => f.write_str(
                "the band is not rows × width pixels, the byte buffer holds under 2 bytes, or an address passes 65535",
            ),
        }
    }
}

impl<S: core::fmt::Debug, P: core::fmt::Debug> core::error::Error for PanelError<S, P> {}

/// A [`BandTarget`] that ships bands to a MIPI-DCS panel.
///
/// # Limits
/// - Pixels are RGB565 only (the panel in COLMOD 0x55).
/// - The band's width is `pixels.len() / rows`; columns are
///   `x_offset..x_offset + width`, rows `y_offset + y..`.
/// - `buf` is the chunk size: each chunk is one SPI transaction; an odd
///   length uses one byte less. It must hold at least 2 bytes.
/// - DC is driven low for each command byte, high for its parameters
///   and the pixels; chip select is the [`SpiDevice`]'s.
#[derive(Debug)]
pub struct Panel<'b, SPI, DC> {
    spi: SPI,
    dc: DC,
    buf: &'b mut [u8],
    x_offset: u16,
    y_offset: u16,
}

impl<'b, SPI: SpiDevice, DC: OutputPin> Panel<'b, SPI, DC> {
    /// A panel with no address offset.
    pub fn new(spi: SPI, dc: DC, buf: &'b mut [u8]) -> Self {
        Self::with_offset(spi, dc, buf, 0, 0)
    }

    /// A panel whose visible area starts at column `x_offset`, row
    /// `y_offset` of its memory (the 240×135 Pico Display: 40, 53).
    pub fn with_offset(spi: SPI, dc: DC, buf: &'b mut [u8], x_offset: u16, y_offset: u16) -> Self {
        Self {
            spi,
            dc,
            buf,
            x_offset,
            y_offset,
        }
    }

    /// The SPI device and pin back.
    pub fn release(self) -> (SPI, DC) {
        (self.spi, self.dc)
    }

    fn command(&mut self, cmd: u8, params: &[u8]) -> Result<(), PanelError<SPI::Error, DC::Error>> {
        self.dc.set_low().map_err(PanelError::Pin)?;
        self.spi.write(&[cmd]).map_err(PanelError::Spi)?;
        if !params.is_empty() {
            self.dc.set_high().map_err(PanelError::Pin)?;
            self.spi.write(params).map_err(PanelError::Spi)?;
        }
        Ok(())
    }
}

fn window(start: u16, len: usize) -> Option<[u8; 4]> {
    let len = u16::try_from(len).ok()?;
    let end = start.checked_add(len)?.checked_sub(1)?;
    let [a, b] = start.to_be_bytes();
    let [c, d] = end.to_be_bytes();
    Some([a, b, c, d])
}

impl<SPI: SpiDevice, DC: OutputPin> BandTarget for Panel<'_, SPI, DC> {
    type Color = Rgb565;
    type Error = PanelError<SPI::Error, DC::Error>;

    fn ship(&mut self, y: u16, rows: u16, pixels: &[Rgb565]) -> Result<(), Self::Error> {
        let rows_n = usize::from(rows);
        if rows_n == 0 || !pixels.len().is_multiple_of(rows_n) || self.buf.len() < 2 {
            return Err(PanelError::Shape);
        }
        let width = pixels.len() / rows_n;
        let cols = window(self.x_offset, width).ok_or(PanelError::Shape)?;
        let row0 = self.y_offset.checked_add(y).ok_or(PanelError::Shape)?;
        let rws = window(row0, rows_n).ok_or(PanelError::Shape)?;
        self.command(CASET, &cols)?;
        self.command(RASET, &rws)?;
        self.command(RAMWR, &[])?;
        self.dc.set_high().map_err(PanelError::Pin)?;
        let per = self.buf.len() / 2;
        for chunk in pixels.chunks(per) {
            let mut n = 0;
            for (p, out) in chunk.iter().zip(self.buf.chunks_exact_mut(2)) {
                out.copy_from_slice(&RawU16::from(*p).into_inner().to_be_bytes());
                n += 2;
            }
            self.spi.write(&self.buf[..n]).map_err(PanelError::Spi)?;
        }
        Ok(())
    }
}

/// Bands of words ([`PackedBand`](super::packed_band::PackedBand)) to
/// the panel: the words already hold the pixels in its byte order, so
/// they are copied into `buf` as their bytes (`u32::to_le_bytes`), with
/// no conversion a pixel, and sent in chunks of `buf` (rounded down to
/// whole words), `2 × rows × width` bytes in all.
impl<SPI: SpiDevice, DC: OutputPin> PackedBandTarget for Panel<'_, SPI, DC> {
    type Color = Rgb565;
    type Error = PanelError<SPI::Error, DC::Error>;

    fn ship_words(
        &mut self,
        y: u16,
        rows: u16,
        width: u16,
        words: &[u32],
    ) -> Result<(), Self::Error> {
        let bytes = 2 * usize::from(rows) * usize::from(width);
        if rows == 0 || width == 0 || words.len() * 4 < bytes || self.buf.len() < 4 {
            return Err(PanelError::Shape);
        }
        let cols = window(self.x_offset, usize::from(width)).ok_or(PanelError::Shape)?;
        let row0 = self.y_offset.checked_add(y).ok_or(PanelError::Shape)?;
        let rws = window(row0, usize::from(rows)).ok_or(PanelError::Shape)?;
        self.command(CASET, &cols)?;
        self.command(RASET, &rws)?;
        self.command(RAMWR, &[])?;
        self.dc.set_high().map_err(PanelError::Pin)?;
        let per = self.buf.len() / 4;
        let mut left = bytes;
        for chunk in words.chunks(per) {
            let mut n = 0;
            for (w, out) in chunk.iter().zip(self.buf.chunks_exact_mut(4)) {
                out.copy_from_slice(&w.to_le_bytes());
                n += 4;
            }
            let n = n.min(left);
            self.spi.write(&self.buf[..n]).map_err(PanelError::Spi)?;
            left -= n;
            if left == 0 {
                break;
            }
        }
        Ok(())
    }
}

/// A MIPI-DCS panel over `embedded-hal-async`'s SPI: [`Panel`]'s bytes,
/// sent by DMA where the HAL does so.
///
/// [`begin`](AsyncBandTarget::begin) sends CASET, RASET and RAMWR; the
/// first poll of [`send`](AsyncBandTarget::send) converts the pixels into
/// `buf` (big-endian RGB565) and starts their transfer. With `buf` of at
/// least `2 × rows × width` bytes the whole band goes in one transfer,
/// all of it while the next band is drawn; with less, it goes in chunks of
/// `buf`, and only the first overlaps the drawing.
///
/// # Limits
/// Those of [`Panel`].
#[derive(Debug)]
pub struct AsyncPanel<'b, SPI, DC> {
    spi: SPI,
    dc: DC,
    buf: &'b mut [u8],
    x_offset: u16,
    y_offset: u16,
}

impl<'b, SPI, DC> AsyncPanel<'b, SPI, DC>
where
    SPI: embedded_hal_async::spi::SpiDevice,
    DC: OutputPin,
{
    /// A panel with no address offset.
    pub fn new(spi: SPI, dc: DC, buf: &'b mut [u8]) -> Self {
        Self::with_offset(spi, dc, buf, 0, 0)
    }

    /// A panel whose visible area starts at column `x_offset`, row
    /// `y_offset` of its memory.
    pub fn with_offset(spi: SPI, dc: DC, buf: &'b mut [u8], x_offset: u16, y_offset: u16) -> Self {
        Self {
            spi,
            dc,
            buf,
            x_offset,
            y_offset,
        }
    }

    /// The SPI device and pin back.
    pub fn release(self) -> (SPI, DC) {
        (self.spi, self.dc)
    }

    async fn command(
        &mut self,
        cmd: u8,
        params: &[u8],
    ) -> Result<(), PanelError<SPI::Error, DC::Error>> {
        self.dc.set_low().map_err(PanelError::Pin)?;
        self.spi.write(&[cmd]).await.map_err(PanelError::Spi)?;
        if !params.is_empty() {
            self.dc.set_high().map_err(PanelError::Pin)?;
            self.spi.write(params).await.map_err(PanelError::Spi)?;
        }
        Ok(())
    }
}

impl<SPI, DC> AsyncBandTarget for AsyncPanel<'_, SPI, DC>
where
    SPI: embedded_hal_async::spi::SpiDevice,
    DC: OutputPin,
{
    type Color = Rgb565;
    type Error = PanelError<SPI::Error, DC::Error>;

    async fn begin(&mut self, y: u16, rows: u16, width: u16) -> Result<(), Self::Error> {
        if rows == 0 || self.buf.len() < 2 {
            return Err(PanelError::Shape);
        }
        let cols = window(self.x_offset, width.into()).ok_or(PanelError::Shape)?;
        let row0 = self.y_offset.checked_add(y).ok_or(PanelError::Shape)?;
        let rws = window(row0, rows.into()).ok_or(PanelError::Shape)?;
        self.command(CASET, &cols).await?;
        self.command(RASET, &rws).await?;
        self.command(RAMWR, &[]).await?;
        self.dc.set_high().map_err(PanelError::Pin)
    }

    async fn send(&mut self, pixels: &[Rgb565]) -> Result<(), Self::Error> {
        let per = self.buf.len() / 2;
        if per == 0 {
            return Err(PanelError::Shape);
        }
        for chunk in pixels.chunks(per) {
            let mut n = 0;
            for (p, out) in chunk.iter().zip(self.buf.chunks_exact_mut(2)) {
                out.copy_from_slice(&RawU16::from(*p).into_inner().to_be_bytes());
                n += 2;
            }
            self.spi
                .write(&self.buf[..n])
                .await
                .map_err(PanelError::Spi)?;
        }
        Ok(())
    }
}
