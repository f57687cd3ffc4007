//! The vertex table of a mesh: the `v`s of one segment, transformed once
//! into view space, which the `f`s after them name by index.
//!
//! The table's memory is the caller's: a slice of [`ViewPoint`]s, as many
//! as the most `v`s of one segment
//! ([`Summary::vertices`](crate::display_list::Summary::vertices), which
//! [`controller::needs`](crate::controller::needs) reports too).
//!
//! A triangle's corners that lie inside the depth range and the window
//! keep their output vertex in their slots
//! ([`Pipeline::mesh_triangle`]): each such vertex is projected once
//! under one projection and window, whatever the faces through it. The
//! table remembers which ([`Pipeline::screen_epoch`]) and forgets them
//! when the pipeline's projection or window changed.

use crate::geometry::{Pipeline, ViewPoint};

use super::SceneError;

/// A segment's mesh vertices in view space, in caller-owned slots.
///
/// # Capacity
/// At most `slots.len()` vertices between two [`clear`](Self::clear)s;
/// one more is [`SceneError::VertexTable`].
#[derive(Debug)]
#[doc(hidden)]
pub struct VertexTable<'v> {
    slots: &'v mut [ViewPoint],
    len: usize,
    /// The [`Pipeline::screen_epoch`] its vertices' kept output vertices
    /// were made under.
    epoch: u32,
}

impl<'v> VertexTable<'v> {
    /// An empty table in `slots`.
    pub fn new(slots: &'v mut [ViewPoint]) -> Self {
        VertexTable {
            slots,
            len: 0,
            epoch: 0,
        }
    }

    /// A table with no slots, for a list or a segment without mesh.
    pub fn none() -> VertexTable<'static> {
        VertexTable {
            slots: &mut [],
            len: 0,
            epoch: 0,
        }
    }

    /// Vertices in the table.
    pub fn len(&self) -> usize {
        self.len
    }

    /// `true` when the table holds no vertex.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Slots of the table.
    pub fn capacity(&self) -> usize {
        self.slots.len()
    }

    /// Empties the table (at a `segment`).
    pub fn clear(&mut self) {
        self.len = 0;
    }

    /// Appends a vertex already in view space.
    pub fn push(&mut self, v: ViewPoint) -> Result<(), SceneError> {
        let capacity = self.slots.len();
        let slot = self
            .slots
            .get_mut(self.len)
            .ok_or(SceneError::VertexTable { capacity })?;
        *slot = v;
        self.len += 1;
        Ok(())
    }

    /// The vertex at 0-based `index`, if the table has it.
    pub fn get(&self, index: usize) -> Option<ViewPoint> {
        self.slots[..self.len].get(index).copied()
    }

    /// `index` if the table has it, [`SceneError::Index`] if not.
    #[inline]
    pub(crate) fn checked(&self, index: usize) -> Result<usize, SceneError> {
        if index < self.len {
            Ok(index)
        } else {
            Err(SceneError::Index {
                index,
                vertices: self.len,
            })
        }
    }

    /// Forgets the kept output vertices when `pipe`'s projection or
    /// window changed since they were made. A run of `v`s and `f`s
    /// changes neither, so it asks once and then reads its slots with
    /// [`synced`](Self::synced). Out of line: inlined, its walk over the
    /// slots costs the run's loop registers on the Cortex-M4.
    #[inline(never)]
    pub(crate) fn sync<const DEPTH: usize, const N: usize>(&mut self, pipe: &Pipeline<DEPTH, N>) {
        if self.epoch != pipe.screen_epoch() {
            self.epoch = pipe.screen_epoch();
            self.slots[..self.len]
                .iter_mut()
                .for_each(ViewPoint::forget_screen);
        }
    }

    /// The table's vertices, for [`Pipeline::mesh_triangle`], with no
    /// look at the pipeline: only after [`sync`](Self::sync) under the
    /// same projection and window.
    #[inline]
    pub(crate) fn synced(&mut self) -> &mut [ViewPoint] {
        &mut self.slots[..self.len]
    }

    /// The vertices at `indices`, for the pipeline; the first index the
    /// table does not have is [`SceneError::Index`].
    pub(crate) fn check(&self, indices: impl Iterator<Item = usize>) -> Result<(), SceneError> {
        for i in indices {
            if i >= self.len {
                return Err(SceneError::Index {
                    index: i,
                    vertices: self.len,
                });
            }
        }
        Ok(())
    }
}
