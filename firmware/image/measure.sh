#!/usr/bin/env bash
# Builds the firmware image, runs it in QEMU, and reports what it costs on
# target: instructions per frame, per polygon and per pixel, the size of
# every variant of the image, and the RAM of rendering with no frame buffer
# (the `budget` variants: their statics are only what the band render of
# their lists needs, read from the ELF's sections and symbols).
#
#   firmware/image/measure.sh           build, run, check, and rewrite what
#                                       it owns in the docs (below)
#   firmware/image/measure.sh --check   the same, but write nothing: print
#                                       the section and exit 1 unless every
#                                       page already holds these figures (CI)
#
# What it owns: in docs/performance.md the blocks between
# `<!-- on-target:begin -->` and `<!-- on-target:end -->` and between
# `<!-- headline-target:begin -->` and `<!-- headline-target:end -->`
# (each marker on a line of its own); and in README.md, CHANGELOG.md,
# docs/*.md and firmware/boards/*/README.md every figure written as `<!-- measure:NAME -->VALUE<!-- /measure -->`
# on one line, NAME one of those `figures` below prints; and
# firmware/image/rows-m4.txt, the racing path's instructions row by row
# (the image built with `--features rows`), to which the race's cost model
# is fitted.
#
# Every frame's checksum must equal the host's (`scanvert checksum` of the
# same lists) and the image must exit with status 0, or this fails.
# Needs qemu-system-arm, and qemu-system-riscv32 for the RISC-V variant.
# Without qemu-system-arm it fails. Without qemu-system-riscv32, --check
# fails, and a rewrite keeps the page's RISC-V subsection as it was (it
# says so on stderr).
set -euo pipefail
# The image and the board are their own workspaces and are built, then
# copied, from their own target directories: a CARGO_TARGET_DIR from the
# caller's shell would build them elsewhere and leave stale ELFs here.
unset CARGO_TARGET_DIR
cd "$(dirname "$0")"
image_dir=$PWD
root=$(cd ../.. && pwd)

mode=write
case "${1:-}" in
  "") ;;
  --check) mode=check ;;
  *) echo "usage: $0 [--check]" >&2; exit 2 ;;
esac

if ! command -v qemu-system-arm >/dev/null; then
  echo "qemu-system-arm not found (Debian: apt-get install qemu-system-arm): nothing measured, nothing written" >&2
  exit 1
fi
if [ "$mode" = check ] && ! command -v qemu-system-riscv32 >/dev/null; then
  echo "qemu-system-riscv32 not found (Debian: apt-get install qemu-system-misc): the RISC-V figures cannot be checked" >&2
  exit 1
fi

arm_target=thumbv7em-none-eabihf
rv_target=riscv32imc-unknown-none-elf
bin=scanvert-image
out=$image_dir/target/measure
mkdir -p "$out"

# The run commands, exactly as CI and the docs give them (with a timeout);
# each is echoed to the log.
qemu_arm() {
  local cmd=(qemu-system-arm -machine mps2-an386 -cpu cortex-m4 -nographic
    -semihosting-config enable=on,target=native -icount shift=0 -kernel "$1")
  echo "+ ${cmd[*]}" >&2
  timeout 60 "${cmd[@]}"
}
qemu_rv() {
  local cmd=(qemu-system-riscv32 -machine virt -nographic -bios none
    -semihosting-config enable=on,target=native -icount shift=0 -kernel "$1")
  echo "+ ${cmd[*]}" >&2
  timeout 60 "${cmd[@]}"
}

# The images are built from a copy of the working tree at a fixed path,
# into their usual target directories. Cargo hashes the absolute path of
# a path dependency outside the building workspace (the library, for the
# image and the board) into its symbol names, and the order of those
# names can tip LLVM's inlining, so built in place the instructions
# counted would depend on where the repository is checked out.
build_root=/tmp/scanvert-measure
rm -rf "$build_root"
mkdir -p "$build_root"
(cd "$root" && tar --exclude=./.git --exclude=target -cf - .) | tar -C "$build_root" -xf -

# Panic locations put source paths into .rodata; remapped to fixed names
# so that the sizes do not depend on where Cargo's home is. (Cargo adds
# these to the rustflags of .cargo/config.toml.)
cargo_home=${CARGO_HOME:-$HOME/.cargo}
build() { # NAME TARGET [cargo args...]: builds and copies the ELF to $out/NAME.elf
  local name=$1 target=$2
  shift 2
  (cd "$build_root/firmware/image" && cargo build --locked --release --target "$target" \
    --target-dir "$image_dir/target" \
    --config "target.$target.rustflags=[\"--remap-path-prefix=$build_root=/scanvert\", \"--remap-path-prefix=$cargo_home=/cargo\"]" \
    "$@" >&2)
  cp "target/$target/release/$bin" "$out/$name.elf"
}

echo "== building the image variants" >&2
build arm-defmt "$arm_target" --features defmt
build arm-discard "$arm_target" --features discard
build arm-halfword "$arm_target" --features halfword
build arm-bands "$arm_target" --features bands
# The racing path's rows, each counted: rows-m4.txt (below).
build arm-rows "$arm_target" --features rows
build arm-budget "$arm_target" --features budget
build arm-budget-poly3 "$arm_target" --features budget-poly3
# The Pico board's rendering core, in the RP2040's instruction set.
build arm-pico thumbv6m-none-eabi --features pico
# The same core on the Cortex-M4F: the panel UI's RAM there.
build arm-ui "$arm_target" --features pico
# The Pico board's firmware itself, for its sections.
pico_dir=$root/firmware/boards/pico-st7789
(cd "$build_root/firmware/boards/pico-st7789" && cargo build --locked --release \
  --target-dir "$pico_dir/target" \
  --config "target.thumbv6m-none-eabi.rustflags=[\"--remap-path-prefix=$build_root=/scanvert\", \"--remap-path-prefix=$cargo_home=/cargo\"]" >&2)
cp "$pico_dir/target/thumbv6m-none-eabi/release/scanvert-pico-st7789" "$out/pico.elf"
if [ "$(uname -m)" != riscv32 ]; then
  build riscv "$rv_target"
fi
build arm "$arm_target"

run() { # NAME QEMU-FUNCTION: runs $out/NAME.elf, output in $out/NAME.log
  local name=$1 q=$2 status=0
  "$q" "$out/$name.elf" </dev/null >"$out/$name.log" || status=$?
  case "$name" in
    *defmt*) echo "$name: $(wc -c <"$out/$name.log") bytes of defmt frames (decode with defmt-print -e $out/$name.elf)" >&2 ;;
    *rows*) echo "$name: $(grep -c '^row ' "$out/$name.log") rows counted one by one (rows-m4.txt)" >&2 ;;
    *) cat "$out/$name.log" >&2 ;;
  esac
  if [ "$status" != 0 ]; then
    echo "$name: the image exited with status $status" >&2
    exit 1
  fi
}

echo "== running in QEMU: $(qemu-system-arm --version | head -n 1)" >&2
run arm qemu_arm
# The defmt variant logs binary frames (decode with defmt-print); only
# its exit status is checked here.
run arm-defmt qemu_arm
# Spans discarded: the count of everything but the pixel writes.
run arm-discard qemu_arm
# The frame as FrameBuffer<Rgb565>, a half-word store a pixel: the
# comparison for the default PackedFrameBuffer.
run arm-halfword qemu_arm
# Every list again band by band (1, 8, 16 and 64 rows), each band's
# checksum the frame's: the image exits non-zero on a mismatch.
run arm-bands qemu_arm
# Each list again a row at a time as colour runs, every row counted.
run arm-rows qemu_arm
# Band by band with no frame buffer, in statics sized for the lists.
run arm-budget qemu_arm
run arm-budget-poly3 qemu_arm
run arm-pico qemu_arm
run arm-ui qemu_arm
# Their stack: QEMU logs the registers at the start of every executed
# block (-d cpu,nochain), and the lowest SP (R13) under the stack's top
# (_stack_start) is the deepest the stack went, to within what one block
# pushes before it branches (a function's prologue is a block's start).
# Hex strings of one width compare as strings in the order of their
# values ("x" keeps awk from reading one as a number).
stack_depth() { # NAME: writes $out/NAME.stack, in bytes
  local elf=$out/$1.elf top low
  top=$(nm "$elf" | awk '$3 == "_stack_start" { print $1 }')
  low=$(qemu-system-arm -machine mps2-an386 -cpu cortex-m4 -nographic \
      -semihosting-config enable=on,target=native -icount shift=0 \
      -d cpu,nochain -D /dev/stderr -kernel "$elf" 2>&1 >/dev/null </dev/null \
    | grep -o 'R13=[0-9a-f]\{8\}' \
    | awk '{ v = "x" substr($0, 5); if (min == "" || v < min) min = v } END { print substr(min, 2) }')
  echo $((16#$top - 16#$low)) >"$out/$1.stack"
  echo "$1: the stack went $(cat "$out/$1.stack") B deep" >&2
}
stack_depth arm-budget
stack_depth arm-budget-poly3
stack_depth arm-pico
stack_depth arm-ui
have_rv=no
if command -v qemu-system-riscv32 >/dev/null; then
  run riscv qemu_rv
  have_rv=yes
else
  echo "qemu-system-riscv32 not found: the RISC-V variant is built, not run; the page's RISC-V subsection is kept as it was" >&2
fi

echo "== checksums: target against host" >&2
(cd "$root" && cargo run --locked --quiet -p scanvert-sim -- checksum firmware/image/scenes/*.scvl firmware/image/scenes/meshes/*.scvl) \
  | sort >"$out/host.sums"
for name in arm arm-halfword $( [ "$have_rv" = yes ] && echo riscv ); do
  # A list rendered again another way (`NAME-paint`, `NAME-crossing`) is
  # checked against the host's checksum of NAME.
  grep '^checksum ' "$out/$name.log" | sed -E 's/^(checksum [^ ]*)-(paint|crossing) /\1 /' \
    | sort -u >"$out/$name.sums"
  if [ "$(grep -c '^checksum ' "$out/$name.log")" -ne \
    $(($(wc -l <"$out/$name.sums") + $(grep -Ec '^checksum [^ ]*-(paint|crossing) ' "$out/$name.log"))) ] \
    || ! diff -u "$out/host.sums" "$out/$name.sums" >&2; then
    echo "$name: checksums differ from the host's" >&2
    exit 1
  fi
  echo "$name: $(grep -c '^checksum ' "$out/$name.log") checksums equal the host's" >&2
done
# The budget variants: every list of theirs, each checksum the host's.
(cd "$root" && cargo run --locked --quiet -p scanvert-sim -- checksum firmware/image/scenes/budget/*.scvl) \
  | cat - "$out/host.sums" | sort >"$out/host-all.sums"
budget_check() { # NAME LISTS: the log's checksums are those of LISTS (file stems) on the host
  local name=$1
  shift
  grep '^checksum ' "$out/$name.log" | sort >"$out/$name.sums"
  for list in "$@"; do grep "^checksum $(basename "$list" .scvl) " "$out/host-all.sums"; done \
    | sort >"$out/$name.want"
  if [ ! -s "$out/$name.want" ] || ! diff -u "$out/$name.want" "$out/$name.sums" >&2; then
    echo "$name: checksums differ from the host's" >&2
    exit 1
  fi
  echo "$name: $(wc -l <"$out/$name.sums") checksums equal the host's" >&2
}
budget_check arm-budget scenes/budget/*.scvl
budget_check arm-budget-poly3 scenes/poly3-layered.scvl scenes/poly3-tilted.scvl

# Section sizes of an ELF: "text rodata data bss image ram" in bytes.
# Image: every allocated section with contents (what is loaded); RAM:
# .data, .bss and .uninit.
sizes() {
  readelf -S -W "$1" | sed -n 's/^ *\[ *[0-9]*\] *//p' |
    while read -r name type _addr _off size _es flags _rest; do
      case "$flags" in *A*) echo "$name $type $((16#$size))" ;; esac
    done | awk '
      $1 == ".text" { text += $3 }
      $1 == ".rodata" { ro += $3 }
      $1 == ".data" { data += $3 }
      $1 == ".bss" || $1 == ".uninit" { bss += $3 }
      $2 == "PROGBITS" { image += $3 }
      END { printf "%d %d %d %d %d %d\n", text, ro, data, bss, image, data + bss }'
}

perf=$root/docs/performance.md
rv_begin='<!-- on-target-riscv:begin -->'
rv_end='<!-- on-target-riscv:end -->'
lists_bytes=$(cat scenes/*.scvl | wc -c)
frame_bytes=$((512 * 256 * 2))
qemu_version=$(qemu-system-arm --version | head -n 1 | sed 's/^QEMU emulator version //')
rustc_version=$(rustc --version)

# W5's frame against the image's two `fill` lines, as a paragraph.
fill_sentence() { # LOG
  awk '
    function c(n,   s) { s = sprintf("%d", n); while (s ~ /[0-9][0-9][0-9][0-9]/) sub(/[0-9][0-9][0-9]($|,)/, ",&", s); return s }
    $1 == "fill" {
      for (i = 3; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
      words = v["words"]; f[$2] = v["instructions"]
    }
    $1 == "frame" && $2 == "w5" {
      for (i = 4; i <= NF; i++) { split($i, kv, "="); if (kv[1] == "instructions") w5 = kv[2] }
    }
    END {
      if (words == "" || w5 == "") exit
      printf "\nW5 against `[u32]::fill` of its %s words (the packed frame holds two\n", c(words)
      printf "pixels a word), counted in the same run (the image'"'"'s `fill` lines):\n"
      printf "%.2f× a fill of a slice whose length is known only at run time, as\n", w5 / f["u32-slice"]
      printf "a span'"'"'s is (%s instructions), and %.2f× a fill of an array of\n", c(f["u32-slice"]), w5 / f["u32-array"]
      printf "fixed length, which the compiler unrolls into paired stores (%s).\n", c(f["u32-array"])
      printf "A span of 32 words or more is stored eight registers an instruction\n"
      printf "(`port/store_multiple.rs`, on Thumb-2 cores); shorter ones as paired stores.\n"
    }' "$1"
}

# The section, in Markdown.
section() {
  cat <<EOF
Written by \`firmware/image/measure.sh\` from one run of the firmware
image in QEMU $qemu_version with \`-icount shift=0\`; do not edit by
hand. The counts repeat exactly from run to run. Compiler: $rustc_version,
\`--release\` with \`opt-level = 3\`, fat LTO, one codegen unit. See
[on-target.md](on-target.md) for the image and how to run it.

### Cortex-M4F (\`thumbv7em-none-eabihf\`, QEMU \`mps2-an386\`)

EOF
  awk '/^calibration:/ { sub(/^calibration: /, ""); print "Counter check: " $0 "." }' "$out/arm.log"
  cat <<'EOF'

Each count is SysTick ticks × 40 around `Controller::render` (list
check, scan conversion, frame-buffer writes; the frame cleared before,
untimed): within 40 of the true count. *Pixels* are those written, a
`clear` counting the whole frame. *Without pixel writes* is the same
render into a port that writes nothing (`--features discard`).
The rates at 168 MHz are **estimates** at one instruction a cycle; a
real Cortex-M4 takes more cycles for many loads, stores and taken
branches, and flash wait states add more.

| scene | frame | polygons | spans | pixels | instructions per frame | per polygon | per pixel | without pixel writes | pixel writes | frames/s at 168 MHz (est.) | polygons/s at 168 MHz (est.) |
|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|
EOF
  table "$out/arm.log"
  cat <<'EOF'

*Polygons* counts `poly` and drawn `poly3` together.
EOF
  fill_sentence "$out/arm.log"
  cat <<'EOF'

#### The 3D layer, stage by stage

The `poly3-*` lists (`testkit::poly3_scenes`) are 170 faces on a
512 × 256 frame, parallel to the screen (*layered*) or tilted through
each other (*tilted*), rendered with the default resolve
(`Resolve::Auto`, which paints them far to near: their spans and pixels
count those painted over too) and again with `Resolve::Crossing` (the
`-crossing` rows: the same checksum). The counter is read where the
controller's hook reports the end of a stage. *Spans*: those the sweep
resolves. *Cut*: the 3D commands, each `poly3` into trapezoids. *Check*:
`Workspace::check`. *Resolve + decode*: `visible::draw`, the background
left as it is.

| scene | poly3 drawn | trapezoids | spans | cut | per poly3 | check | resolve + decode | per span | without pixel writes | whole render | frames/s at 168 MHz (est.) | resolve + decode only, frames/s (est.) |
|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|
EOF
  stages_table "$out/arm.log"
  cat <<EOF

#### Meshes, 240 × 240, in 16-row bands

The mesh lists (\`scenes/meshes/\`, from \`testkit::meshes\`, written as
\`scanvert import\` writes a model: \`v\`/\`f\` lines, a fitted view and a
light) rendered with \`Controller::render_bands_packed\` (a band of words,
two pixels a word in the panel's byte order) and no frame buffer,
each band shipped nowhere in the timed render (as a DMA transfer costs
the CPU nothing a pixel), then into the frame's checksum (the host's)
in a second render, not timed. *Triangles*: the list's \`f\`s; *drawn*:
those that reached the 3D layer. *Instructions* with the default
resolve (\`Resolve::Auto\`, which takes the sweep's crossing points for
these small trapezoids), *painted* with \`Resolve::Paint\`. Their statics (\`src/meshes.rs\`,
\`MESH_*\`): $(thousands "$(symbols "$out/arm.elf" 'MESH_')") B, of which the band buffer
$(thousands "$(field "$out/arm.log" meshes band)") B and the vertex table $(thousands "$(field "$out/arm.log" meshes vertices)") B.

| mesh | frame | band rows | triangles | vertices | drawn | trapezoids | most on a row | instructions | painted | frames/s at 168 MHz (est.) | RV32IMC instructions |
|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|
EOF
  mesh_table "$out/arm.log" "$out/riscv.log"
  cat <<'EOF'

#### Which resolve a frame takes

The default resolve, `Resolve::Auto`, chooses once a frame between the
sweep's crossing points (`Resolve::Crossing`) and painting far to near
(`Resolve::Paint`), which draw the same pixels: it paints when the
frame's trapezoids are at least `PAINT_FROM` rows tall on
average. Painting pays for each trapezoid that enters (its tests against
the live ones) and saves on each row of one. Instructions a frame, both
ways, from the runs above (the 170-face lists in 16-row bands; the
meshes as their table gives them); the default's are in bold:

| list | trapezoids | crossing points | painted | the default took (its line's `mode`) |
|---|--:|--:|--:|---|
EOF
  resolve_table "$out/arm.log" "$out/arm-bands.log"
  cat <<'EOF'

#### Targets of the 3D layer in 16-row bands

The frames above against the instructions a frame the 3D layer is held
to in 16-row bands, with the default resolve: each mesh list at most
1,500,000 (over 110 frames/s at 168 MHz), `poly3-layered` at most
900,000 and `poly3-tilted` at most 1,200,000.

| list | target | measured | verdict |
|---|--:|--:|---|
EOF
  targets_table "$out/arm.log" "$out/arm-bands.log"
  cat <<'EOF'

#### Two pixels to a word

The image renders into `PackedFrameBuffer` (`port/packed.rs`, two
RGB565 pixels to a `u32`); built with `--features halfword`, into
`FrameBuffer<Rgb565>`, one `strh` a pixel, with the same checksums.

| scene | `FrameBuffer` | `PackedFrameBuffer` | packed per pixel | `FrameBuffer` ÷ packed |
|---|--:|--:|--:|--:|
EOF
  packed_table "$out/arm-halfword.log" "$out/arm.log"
  cat <<'EOF'

#### Band by band, with no frame buffer

Built with `--features bands`, the image renders every list again
through `Controller::render_bands_packed` into one band buffer of words
(`PackedBand`: two RGB565 pixels a word, in the panel's byte order), in
bands of 1, 8, 16 and 64 rows, each band's checksum chained into the
frame's, which equals the host's. Each ratio is over the
`PackedFrameBuffer` full frame above, which writes its pixels a word at
a time too; a band is filled with the background where the full frame
was cleared before, untimed.

| list | full frame (`PackedFrameBuffer`) | 1 row | 8 rows | 16 rows | 64 rows | 16 rows, instructions |
|---|--:|--:|--:|--:|--:|--:|
EOF
  bands_table "$out/arm-bands.log" "$out/arm.log"
  echo
  echo "$rv_begin"
  if [ "$have_rv" = yes ]; then
    cat <<'EOF'
### RV32IMC soft-core (`riscv32imc-unknown-none-elf`, QEMU `virt`)

The same image and lists, counted exactly with `minstret` (no FPU, no
atomics). *vs M4F*: the instruction count over the Cortex-M4F's.

| scene | instructions per frame | per polygon | per pixel | vs M4F |
|---|--:|--:|--:|--:|
EOF
    rv_table "$out/riscv.log" "$out/arm.log"
  else
    # Not run here: the page's subsection as it was.
    block "$perf" "$rv_begin" "$rv_end"
  fi
  echo "$rv_end"
  cat <<EOF

### Image size

Bytes per section, from \`readelf -S\`. *Flash* is everything loaded
(vector table, \`.text\`, \`.rodata\`, \`.data\`); *static RAM* is
\`.data\` + \`.bss\`, stack not included. \`.rodata\` holds the embedded
display lists ($(thousands "$lists_bytes") B); \`.bss\` holds the
512 × 256 RGB565 frame buffer ($(thousands "$frame_bytes") B). The
columns *without* subtract those two, leaving the code and data of
scanvert, the runtime, the log formatting and the image itself.

| variant | \`.text\` | \`.rodata\` | \`.data\` | \`.bss\` | flash | static RAM | flash without lists | RAM without frame buffer |
|---|--:|--:|--:|--:|--:|--:|--:|--:|
EOF
  size_row "Cortex-M4F, plain text log" "$out/arm.elf"
  size_row "Cortex-M4F, \`defmt\` feature" "$out/arm-defmt.elf"
  if [ -f "$out/riscv.elf" ]; then
    size_row "RV32IMC (all in RAM), plain text log" "$out/riscv.elf"
  fi
  budget_section
}

# The value of KEY in the first line of LOG whose first word is WORD.
field() { # LOG WORD KEY
  awk -v w="$2" -v k="$3" '$1 == w {
    for (i = 2; i <= NF; i++) { n = index($i, "="); if (n && substr($i, 1, n - 1) == k) { print substr($i, n + 1); exit } }
  }' "$1"
}

# Bytes of the statics of ELF whose demangled names match PATTERN.
symbols() { # ELF PATTERN
  local total=0 _addr size type name
  while read -r _addr size type name; do
    case "$type" in [bBdD]) if [[ $name =~ $2 ]]; then total=$((total + 16#$size)); fi ;; esac
  done < <(nm -S -C "$1")
  echo "$total"
}

kib() { fmt "$(awk -v b="$1" 'BEGIN { print b / 1024 }')" 1; }

# The RAM of the budget variants, by part: the scene storage's pools from
# the image's `budget` line (slots × slot size), the statics from their
# symbols, the total from the sections.
budget_section() {
  local demo=$out/arm-budget poly=$out/arm-budget-poly3 k
  local demo_data demo_bss demo_ram poly_data poly_bss poly_ram
  read -r _ _ demo_data demo_bss _ demo_ram < <(sizes "$demo.elf")
  read -r _ _ poly_data poly_bss _ poly_ram < <(sizes "$poly.elf")
  cat <<EOF

### RAM with no frame buffer: the budget variants

Built with \`--features budget\`, the image renders only the README's
3D demo at 320 × 240 (its 8 frames, as display lists from
\`scanvert_sim::demo::frame_list\`) with \`Controller::render_bands_packed\` in
bands of $(field "$demo.log" budget band_rows) rows and no frame buffer; with \`--features budget-poly3\`, the
two 170-face lists at 512 × 256. Every band's checksum chains into the
host's. The statics (\`src/budget.rs\`) hold only what the lists need
(\`controller::needs\`, \`DisplayList::table_needs\`). *Total* is
\`.data\` + \`.bss\` (\`readelf -S\`); the parts are symbol sizes
(\`nm -S\`) and the image's own count of its pools. *Stack* is the
deepest it went in the run (the lowest stack pointer QEMU logs at the
start of a block), to within what one block pushes.

| part | demo, 320 × 240 | 170-face lists, 512 × 256 |
|---|--:|--:|
EOF
  budget_row "trapezoids" \
    "$(thousands "$(field "$demo.log" budget trapezoids)") ($(field "$demo.log" budget trapezoid_slots) × $(field "$demo.log" budget trapezoid_size) B)" \
    "$(thousands "$(field "$poly.log" budget trapezoids)") ($(field "$poly.log" budget trapezoid_slots) × $(field "$poly.log" budget trapezoid_size) B)"
  for k in faces segments index edge_slots runs labels text; do
    budget_row "${k/_/ }" "$(field "$demo.log" budget "$k")" "$(field "$poly.log" budget "$k")"
  done
  budget_row "workspace ($(field "$demo.log" budget active_slots) / $(field "$poly.log" budget active_slots) active entries)" \
    "$(field "$demo.log" budget workspace)" "$(field "$poly.log" budget workspace)"
  budget_row "= scene storage (\`BUDGET_SCENE\`)" "$(symbols "$demo.elf" BUDGET_SCENE)" "$(symbols "$poly.elf" BUDGET_SCENE)"
  budget_row "band buffer (\`BUDGET_BAND\`, RGB565)" "$(symbols "$demo.elf" BUDGET_BAND)" "$(symbols "$poly.elf" BUDGET_BAND)"
  budget_row "2D edge table and rasteriser edges (\`BUDGET_TABLE_*\`, \`BUDGET_EDGES\`)" \
    "$(symbols "$demo.elf" 'BUDGET_(TABLE|EDGES)')" "$(symbols "$poly.elf" 'BUDGET_(TABLE|EDGES)')"
  budget_row "the rest (runtime, counter)" \
    "$((demo_ram - $(symbols "$demo.elf" BUDGET_)))" "$((poly_ram - $(symbols "$poly.elf" BUDGET_)))"
  echo "| **total static RAM** (\`.data\` + \`.bss\`: $(thousands "$demo_data") + $(thousands "$demo_bss"); $(thousands "$poly_data") + $(thousands "$poly_bss")) | **$(thousands "$demo_ram")** ($(kib "$demo_ram") KiB) | **$(thousands "$poly_ram")** ($(kib "$poly_ram") KiB) |"
  echo "| within 64 KiB (65,536 B)? | $(within "$demo_ram") | $(within "$poly_ram") |"
  local demo_stack poly_stack
  demo_stack=$(cat "$demo.stack")
  poly_stack=$(cat "$poly.stack")
  budget_row "stack, the deepest it went (measured)" "$demo_stack" "$poly_stack"
  budget_row "static RAM and stack" "$((demo_ram + demo_stack))" "$((poly_ram + poly_stack))"
  echo "| static RAM and stack within 64 KiB? | $(within $((demo_ram + demo_stack))) | $(within $((poly_ram + poly_stack))) |"
  budget_row "against a full RGB565 frame buffer" "$(against $((320 * 240 * 2)) "$demo_ram")" "$(against $((512 * 256 * 2)) "$poly_ram")"
  budget_row "against a z-buffer renderer's frame + 16-bit depth" "$(against $((320 * 240 * 4)) "$demo_ram")" "$(against $((512 * 256 * 4)) "$poly_ram")"
  budget_row "against a z-buffer renderer's frame + 32-bit depth" "$(against $((320 * 240 * 6)) "$demo_ram")" "$(against $((512 * 256 * 6)) "$poly_ram")"
  cat <<'EOF'

The demo's 8 frames in one row (the least and the most of each column):

| list | frame | trapezoids | most on a row | instructions (bands and checksum) | frames/s at 168 MHz (est.) |
|---|---|--:|--:|--:|--:|
EOF
  awk '$1 == "bands" {
    for (i = 4; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] }
    print $2, $3, f["trapezoids"], f["max_active"], f["instructions"]
  }' "$demo.log" "$poly.log" | awk '
    # The demo frames (demo-WxH-NN) as one row: "demo-WxH-00..07 WxH lo-hi ...".
    $1 ~ /^demo-/ {
      n++; stem = $1; sub(/-[0-9]+$/, "", stem); frame = $2
      if (n == 1) { first = $1; t0 = t1 = $3; a0 = a1 = $4; i0 = i1 = $5 }
      last = $1
      if ($3 < t0) t0 = $3; if ($3 > t1) t1 = $3
      if ($4 < a0) a0 = $4; if ($4 > a1) a1 = $4
      if ($5 < i0) i0 = $5; if ($5 > i1) i1 = $5
      next
    }
    { rest[++m] = $0 }
    END {
      if (n) print stem "-" substr(first, length(stem) + 2) "…" substr(last, length(stem) + 2), frame, t0 "–" t1, a0 "–" a1, i0 "–" i1
      for (j = 1; j <= m; j++) print rest[j]
    }' | while read -r name frame traps active instr; do
    local lo=${instr%–*} hi=${instr#*–} rate
    rate=$(fmt "$(awk -v i="$hi" 'BEGIN { print 168e6 / i }')" 1)
    if [ "$lo" != "$hi" ]; then
      rate="$rate–$(fmt "$(awk -v i="$lo" 'BEGIN { print 168e6 / i }')" 1)"
      instr="$(thousands "$lo")–$(thousands "$hi")"
    else
      instr=$(thousands "$instr")
    fi
    echo "| $name | ${frame/x/×} | $traps | $active | $instr | $rate |"
  done
}

budget_row() { # LABEL DEMO POLY: a row of bytes (plain numbers get separators) or text
  local a=$2 b=$3
  case "$a" in *[!0-9]*) ;; *) a=$(thousands "$a") ;; esac
  case "$b" in *[!0-9]*) ;; *) b=$(thousands "$b") ;; esac
  echo "| $1 | $a | $b |"
}

within() { # BYTES
  if [ "$1" -le 65536 ]; then
    echo "**yes**, $(thousands $((65536 - $1))) B to spare"
  else
    echo "**no**, $(thousands $(($1 - 65536))) B over"
  fi
}

against() { # OTHER BYTES: "OTHER B (× OTHER/BYTES)"
  echo "$(thousands "$1") B ($(fmt "$(awk -v o="$1" -v b="$2" 'BEGIN { print o / b }')" 1)×)"
}

thousands() { printf "%s" "$1" | sed -e ':a' -e 's/\([0-9]\)\([0-9]\{3\}\)\($\|[,.]\)/\1,\2\3/;ta'; }

size_row() { # LABEL ELF
  read -r text ro data bss image ram < <(sizes "$2")
  echo "| $1 | $(thousands "$text") | $(thousands "$ro") | $(thousands "$data") | $(thousands "$bss") | $(thousands "$image") | $(thousands "$ram") | $(thousands $((image - lists_bytes))) | $(thousands $((ram - frame_bytes))) |"
}

# "frame NAME WxH commands=.. polygons=.. clears=.. spans=.. pixels=.. ticks=.. instructions=.."
# as "NAME W H polygons clears spans pixels instructions"; the mesh
# frames (`frame mesh-…`, in bands) are mesh_frames'.
frames() {
  awk '$1 == "frame" && $2 !~ /^mesh-/ {
    split($3, wh, "x")
    for (i = 4; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] }
    print $2, wh[1], wh[2], f["polygons"] + f["poly3"], f["clears"], f["spans"], f["pixels"], f["instructions"]
  }' "$1"
}

# Instructions of NAME in LOG.
instructions_of() { frames "$2" | awk -v n="$1" '$1 == n { print $8 }'; }

# "frame mesh-NAME WxH rows=.. vertices=.. faces=.. drawn=.. culled=.. trapezoids=.. max_active=.. ticks=.. instructions=.."
# as "NAME WxH rows vertices faces drawn trapezoids max_active instructions".
mesh_frames() {
  awk '$1 == "frame" && $2 ~ /^mesh-/ {
    for (i = 4; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] }
    print $2, $3, f["rows"], f["vertices"], f["faces"], f["drawn"], f["trapezoids"], f["max_active"], f["instructions"]
  }' "$1"
}

# Instructions of mesh frame NAME in LOG ("n/a" if the log has none).
mesh_instructions() { # NAME LOG
  local v=""
  [ -f "$2" ] && v=$(mesh_frames "$2" | awk -v n="$1" '$1 == n { print $9 }')
  if [ -n "$v" ]; then thousands "$v"; else echo n/a; fi
}

# Crossing points against painting, for the lists drawn both ways: the
# 170-face lists in 16-row bands (BANDS-LOG; the default paints them),
# the meshes (ARM-LOG; the default takes crossing points).
resolve_table() { # ARM-LOG BANDS-LOG
  local name traps auto other mode
  for name in poly3-layered poly3-tilted; do
    traps=$(frame_key "$1" "$name" trapezoids)
    mode=$(frame_key "$1" "$name" mode)
    auto=$(bands_of "$2" | awk -v n="$name" '$1 == n && $2 == 16 { print $3 }')
    other=$(bands_of "$2" | awk -v n="$name-crossing" '$1 == n && $2 == 16 { print $3 }')
    if [ "$mode" = paint ]; then
      echo "| $name, 16-row bands | $(thousands "$traps") | $(thousands "$other") | **$(thousands "$auto")** | $mode |"
    else
      echo "| $name, 16-row bands | $(thousands "$traps") | **$(thousands "$auto")** | n/a | $mode |"
    fi
  done
  mesh_frames "$1" | while read -r name frame rows vertices faces drawn traps active instr; do
    case "$name" in *-paint) continue ;; esac
    mode=$(frame_key "$1" "$name" mode)
    if [ "$mode" = paint ]; then
      echo "| $name | $(thousands "$traps") | n/a | **$(thousands "$instr")** | $mode |"
    else
      echo "| $name | $(thousands "$traps") | **$(thousands "$instr")** | $(mesh_instructions "$name-paint" "$1") | $mode |"
    fi
  done
}

# A line of the targets' table: NAME TARGET MEASURED.
target_row() {
  local verdict
  if [ "$3" -le "$2" ]; then
    verdict='**met**'
  else
    verdict="missed: $(fmt "$(awk -v m="$3" -v t="$2" 'BEGIN { print m / t }')" 2)× the target"
  fi
  echo "| $1 | $(thousands "$2") | $(thousands "$3") | $verdict |"
}

targets_table() { # ARM-LOG BANDS-LOG
  local name frame rows vertices faces drawn traps active instr
  mesh_frames "$1" | while read -r name frame rows vertices faces drawn traps active instr; do
    case "$name" in *-paint) continue ;; esac
    target_row "$name" 1500000 "$instr"
  done
  target_row poly3-layered 900000 "$(bands_of "$2" | awk '$1 == "poly3-layered" && $2 == 16 { print $3 }')"
  target_row poly3-tilted 1200000 "$(bands_of "$2" | awk '$1 == "poly3-tilted" && $2 == 16 { print $3 }')"
}

# The value of KEY on the frame line of NAME in LOG.
frame_key() { # LOG NAME KEY
  awk -v n="$2" -v k="$3" '$1 == "frame" && $2 == n {
    for (i = 3; i <= NF; i++) { split($i, kv, "="); if (kv[1] == k) print kv[2] }
  }' "$1"
}

mesh_table() { # ARM-LOG RV-LOG
  mesh_frames "$1" | while read -r name frame rows vertices faces drawn traps active instr; do
    case "$name" in *-paint) continue ;; esac
    echo "| ${name#mesh-} | ${frame/x/×} | $rows | $(thousands "$faces") | $(thousands "$vertices") | $(thousands "$drawn") | $(thousands "$traps") | $active | **$(thousands "$instr")** | $(mesh_instructions "$name-paint" "$1") | $(fmt "$(awk -v i="$instr" 'BEGIN { print 168e6 / i }')" 1) | $(mesh_instructions "$name" "$2") |"
  done
}

fmt() { # NUMBER DECIMALS
  thousands "$(awk -v v="$1" -v d="$2" 'BEGIN { printf("%." d "f", v) }')"
}

table() {
  frames "$1" | while read -r name w h polys clears spans pixels instr; do
    written=$((pixels + clears * w * h))
    per_poly="n/a"; poly_rate="n/a"
    if [ "$polys" -gt 0 ]; then
      per_poly=$(fmt "$(awk -v i="$instr" -v p="$polys" 'BEGIN { print i / p }')" 0)
      poly_rate=$(fmt "$(awk -v i="$instr" -v p="$polys" 'BEGIN { print 168e6 * p / i }')" 0)
    fi
    per_px=$(fmt "$(awk -v i="$instr" -v p="$written" 'BEGIN { print i / p }')" 2)
    fps=$(fmt "$(awk -v i="$instr" 'BEGIN { print 168e6 / i }')" 1)
    scan=$(instructions_of "$name" "$out/arm-discard.log")
    writes=$(fmt "$(awk -v i="$instr" -v s="$scan" 'BEGIN { print 100 * (i - s) / i }')" 0)
    echo "| $name | ${w}×${h} | $(thousands "$polys") | $(thousands "$spans") | $(thousands "$written") | $(thousands "$instr") | $per_poly | $per_px | $(thousands "$scan") | ${writes} % | $fps | $poly_rate |"
  done
}

# "stages NAME faces=.. trapezoids=.. cut=.. check=.. resolve=.. ..." as
# "NAME faces trapezoids cut check resolve spans", spans being those the
# sweep resolved (empty, single, multiple and intersecting).
stages() {
  awk '$1 == "stages" {
    for (i = 3; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] }
    print $2, f["faces"], f["trapezoids"], f["cut"], f["check"], f["resolve"],
      f["empty"] + f["single"] + f["multiple"] + f["intersecting"]
  }' "$1"
}

stages_table() { # ARM-LOG
  stages "$1" | while read -r name faces traps cut check resolve spans; do
    total=$(instructions_of "$name" "$1")
    scan=$(stages "$out/arm-discard.log" | awk -v n="$name" '$1 == n { print $6 }')
    per_face=$(fmt "$(awk -v c="$cut" -v f="$faces" 'BEGIN { print c / f }')" 0)
    per_span=n/a
    if [ "$spans" -gt 0 ]; then
      per_span=$(fmt "$(awk -v r="$resolve" -v s="$spans" 'BEGIN { print r / s }')" 0)
    fi
    fps=$(fmt "$(awk -v i="$total" 'BEGIN { print 168e6 / i }')" 1)
    fps_r=$(fmt "$(awk -v i="$resolve" 'BEGIN { print 168e6 / i }')" 1)
    shown=n/a
    [ "$spans" -gt 0 ] && shown=$(thousands "$spans")
    echo "| $name | $(thousands "$faces") | $(thousands "$traps") | $shown | $(thousands "$cut") | $per_face | $(thousands "$check") | $(thousands "$resolve") | $per_span | $(thousands "$scan") | $(thousands "$total") | $fps | $fps_r |"
  done
}

packed_table() { # HALFWORD-LOG PACKED-LOG
  frames "$2" | while read -r name w h polys clears spans pixels instr; do
    written=$((pixels + clears * w * h))
    base=$(instructions_of "$name" "$1")
    per_px=$(fmt "$(awk -v i="$instr" -v p="$written" 'BEGIN { print i / p }')" 2)
    ratio=$(fmt "$(awk -v b="$base" -v p="$instr" 'BEGIN { print b / p }')" 2)
    echo "| $name | $(thousands "$base") | $(thousands "$instr") | $per_px | ${ratio}× |"
  done
}

# "bands NAME rows=R instructions=I ..." as "NAME R I".
bands_of() {
  awk '$1 == "bands" && $3 ~ /^rows=/ {
    for (i = 3; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] }
    print $2, f["rows"], f["instructions"]
  }' "$1"
}

bands_table() { # BANDS-LOG FULL-FRAME-LOG
  frames "$2" | while read -r name w h polys clears spans pixels base; do
    # Lists the band renders draw (not those drawn again another way).
    bands_of "$1" | awk -v n="$name" '$1 == n { found = 1 } END { exit !found }' || continue
    row="| $name | $(thousands "$base")"
    for rows in 1 8 16 64; do
      instr=$(bands_of "$1" | awk -v n="$name" -v r="$rows" '$1 == n && $2 == r { print $3 }')
      row="$row | $(fmt "$(awk -v i="$instr" -v b="$base" 'BEGIN { print i / b }')" 2)×"
      [ "$rows" = 16 ] && at16=$instr
    done
    echo "$row | $(thousands "$at16") |"
  done
}

rv_table() { # RISCV-LOG ARM-LOG
  frames "$1" | while read -r name w h polys clears spans pixels instr; do
    written=$((pixels + clears * w * h))
    per_poly="n/a"
    if [ "$polys" -gt 0 ]; then
      per_poly=$(fmt "$(awk -v i="$instr" -v p="$polys" 'BEGIN { print i / p }')" 0)
    fi
    per_px=$(fmt "$(awk -v i="$instr" -v p="$written" 'BEGIN { print i / p }')" 2)
    arm=$(instructions_of "$name" "$out/arm.log")
    ratio=$(fmt "$(awk -v r="$instr" -v a="$arm" 'BEGIN { print r / a }')" 2)
    echo "| $name | $(thousands "$instr") | $per_poly | $per_px | ${ratio}× |"
  done
}

# The lines strictly between the marker lines BEGIN and END of FILE (each
# marker a line of its own, surrounding spaces allowed).
block() { # FILE BEGIN END
  awk -v b="$2" -v e="$3" '
    { line = $0; gsub(/^[ \t]+|[ \t]+$/, "", line) }
    line == e && inside { exit }
    inside { print }
    line == b { inside = 1 }' "$1"
}

# FILE with the lines between the marker lines BEGIN and END replaced by
# those of CONTENT; fails if FILE lacks either marker.
splice() { # FILE BEGIN END CONTENT
  if ! grep -qxF "$2" "$1" || ! grep -qxF "$3" "$1"; then
    echo "$1 has no markers $2 ... $3" >&2
    return 1
  fi
  awk -v b="$2" -v e="$3" -v f="$4" '
    { line = $0; gsub(/^[ \t]+|[ \t]+$/, "", line) }
    line == b && !done { print; while ((getline l < f) > 0) print l; skip = 1; next }
    line == e && skip { print; skip = 0; done = 1; next }
    !skip { print }' "$1"
}

# Frames per second at 168 MHz for an instruction count.
fps() { fmt "$(awk -v i="$1" 'BEGIN { print 168e6 / i }')" 1; }

# The first screen of docs/performance.md: the Cortex-M4 figures a reader
# looks for first.
headline() {
  local demo=$out/arm-budget demo_ram demo_stack lo hi polys instr
  read -r _ _ _ _ _ demo_ram < <(sizes "$demo.elf")
  demo_stack=$(cat "$demo.stack")
  read -r lo hi < <(awk '$1 == "bands" && $2 ~ /^demo-/ {
      for (i = 4; i <= NF; i++) { split($i, kv, "="); if (kv[1] == "instructions") v = kv[2] }
      if (min == "" || v + 0 < min + 0) min = v; if (v + 0 > max + 0) max = v
    } END { print min, max }' "$demo.log")
  read -r polys instr < <(frames "$out/arm.log" | awk '$1 == "w1" { print $4, $8 }')
  cat <<EOF
| Cortex-M4F, instructions counted in QEMU (rates at 168 MHz assume one instruction a cycle: upper estimates) | |
|---|--:|
| W1, 30 × 30 squares into a 256 × 256 frame | $(fmt "$(awk -v p="$polys" -v i="$instr" 'BEGIN { print 168e6 * p / i }')" 0) polygons/s ($(fmt "$(awk -v p="$polys" -v i="$instr" 'BEGIN { print i / p }')" 0) instructions a polygon) |
| 2D demo (\`scenes/demo.dl\`), 320 × 200 | $(fps "$(instructions_of demo "$out/arm.log")") frames/s |
| 170 faces, 512 × 256, layered / tilted (the default, \`Resolve::Auto\`: painted far to near) | $(fps "$(instructions_of poly3-layered "$out/arm.log")") / $(fps "$(instructions_of poly3-tilted "$out/arm.log")") frames/s |
| the same with the sweep's crossing points (\`Resolve::Crossing\`) | $(fps "$(instructions_of poly3-layered-crossing "$out/arm.log")") / $(fps "$(instructions_of poly3-tilted-crossing "$out/arm.log")") frames/s |
| 3D demo, 320 × 240, in 16-row bands with no frame buffer (8 frames) | $(fps "$hi") to $(fps "$lo") frames/s |
| its static RAM (\`.data\` + \`.bss\`) | **$(thousands "$demo_ram") B** |
| its static RAM and deepest stack ($(thousands "$demo_stack") B) | **$(thousands $((demo_ram + demo_stack))) B**: $(within $((demo_ram + demo_stack))) in 64 KiB |
EOF
}

# The figures quoted in prose, one "NAME<tab>VALUE" a line: what a
# `<!-- measure:NAME -->` span holds.
figures() {
  local name elf ram stack polys instr
  for name in demo poly3; do
    case $name in demo) elf=arm-budget ;; *) elf=arm-budget-poly3 ;; esac
    read -r _ _ _ _ _ ram < <(sizes "$out/$elf.elf")
    stack=$(cat "$out/$elf.stack")
    printf 'budget-%s-static\t%s B\n' "$name" "$(thousands "$ram")"
    printf 'budget-%s-stack\t%s B\n' "$name" "$(thousands "$stack")"
    printf 'budget-%s-total\t%s B\n' "$name" "$(thousands $((ram + stack)))"
  done
  read -r polys instr < <(frames "$out/arm.log" | awk '$1 == "w1" { print $4, $8 }')
  mesh_frames "$out/arm.log" | while read -r name _ _ _ _ _ _ _ instr; do
    printf '%s-instructions\t%s\n' "$name" "$(thousands "$instr")"
  done
  printf 'w1-polygons-per-second\t%s\n' "$(fmt "$(awk -v p="$polys" -v i="$instr" 'BEGIN { print 168e6 * p / i }')" 0)"
  pico_figures
}

# The Pico board (firmware/boards/pico-st7789): its firmware's sections,
# and its rendering core's frames and stack from the `pico` variant. A
# frame's time is its instructions at 125 MHz, one a cycle (an upper
# estimate of the speed: the Cortex-M0+ takes two cycles for loads and
# taken branches, and runs from the flash's cache), plus its rows sent
# over SPI at 62.5 MHz (240 pixels of 16 bits a row), which blocks.
pico_figures() {
  local text data bss rows frames most median stack
  read -r text _ data bss _ _ < <(sizes "$out/pico.elf")
  stack=$(cat "$out/arm-pico.stack")
  read -r frames rows most < <(awk '$1 == "pico" && $2 ~ /^frames=/ {
      sub("frames=", "", $2); sub("rows=", "", $3); sub("most=", "", $4); print $2, $3, $4 }' "$out/arm-pico.log")
  median=$(awk '$1 == "pico" && $2 == "frame" { sub("instructions=", "", $5); print $5 }' "$out/arm-pico.log" |
    sort -n | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }')
  printf 'pico-static\t%s B\n' "$(thousands $((data + bss)))"
  printf 'pico-text\t%s KiB\n' "$(( (text + 512) / 1024 ))"
  printf 'pico-stack\t%s B\n' "$(thousands "$stack")"
  printf 'pico-ram\t%s B\n' "$(thousands $((data + bss + stack)))"
  printf 'pico-instructions-median\t%s\n' "$(thousands "$median")"
  printf 'pico-instructions-most\t%s\n' "$(thousands "$most")"
  printf 'pico-rows\t%s of %s\n' "$(thousands "$rows")" "$(thousands $((frames * 240)))"
  printf 'pico-fps-full\t%s\n' "$(fmt "$(awk -v i="$most" 'BEGIN { print 1 / (i / 125e6 + 240 * 240 * 16 / 62.5e6) }')" 0)"
  local ui_memory ui_stack
  ui_memory=$(awk '$1 == "pico" && $2 ~ /^frames=/ { sub("memory=", "", $5); print $5 }' "$out/arm-ui.log")
  ui_stack=$(cat "$out/arm-ui.stack")
  printf 'ui-m4-memory\t%s B\n' "$(thousands "$ui_memory")"
  printf 'ui-m4-stack\t%s B\n' "$(thousands "$ui_stack")"
  printf 'ui-m4-ram\t%s B\n' "$(thousands $((ui_memory + ui_stack)))"
  printf 'pico-fps-median\t%s\n' "$(fmt "$(awk -v i="$median" -v r="$rows" -v f="$frames" 'BEGIN { print 1 / (i / 125e6 + r / f * 240 * 16 / 62.5e6) }')" 0)"
}

# FILE with every `<!-- measure:NAME -->…<!-- /measure -->` span holding
# NAME's value from FIGURES; an unknown NAME fails.
spans() { # FIGURES FILE
  perl -e '
    my ($figures, $file) = @ARGV;
    my %v;
    open(my $f, "<", $figures) or die "$figures: $!";
    while (<$f>) { chomp; my ($k, $x) = split /\t/, $_, 2; $v{$k} = $x }
    open(my $t, "<", $file) or die "$file: $!";
    my $bad = 0;
    while (my $line = <$t>) {
      $line =~ s{(<!-- measure:([A-Za-z0-9_-]+) -->)(.*?)(<!-- /measure -->)}{
        if (exists $v{$2}) { "$1$v{$2}$4" }
        else { print STDERR "$file:$.: no figure named $2\n"; $bad = 1; "$1$3$4" }
      }ge;
      print $line;
    }
    exit $bad;' "$1" "$2"
}

section >"$out/section.md"
echo "== on-target figures" >&2
cat "$out/section.md"
headline >"$out/headline.md"
figures >"$out/figures.tsv"
echo "== figures quoted in prose" >&2
cat "$out/figures.tsv" >&2

# `true` when pages $1 and $2 differ only in the image-size table's rows
# (`| Cortex-M… | 130,832 | …` and `| RV32… | …`), each number within 64
# bytes: the same source built in another clone (CI's) has moved `.text` by a
# few bytes of alignment, which is no stale figure. Every other line,
# and every instruction count, must be equal.
sizes_near() {
  awk -v a="$1" -v b="$2" 'BEGIN {
    while ((getline x < a) > 0) { if ((getline y < b) <= 0) exit 1
      if (x == y) continue
      if (x !~ /^\| (Cortex-M|RV32)/ || y !~ /^\| (Cortex-M|RV32)/) exit 1
      n = split(x, p, "|"); if (split(y, q, "|") != n) exit 1
      for (i = 1; i <= n; i++) { u = p[i]; v = q[i]; gsub(/[ ,]/, "", u); gsub(/[ ,]/, "", v)
        if (u == v) continue
        if (u !~ /^[0-9]+$/ || v !~ /^[0-9]+$/) exit 1
        d = u - v; if (d < 0) d = -d; if (d > 64) exit 1 } }
    if ((getline y < b) > 0) exit 1 }'
}

# Each page as it should be, against the page as it is.
mkdir -p "$out/pages"
splice "$perf" '<!-- on-target:begin -->' '<!-- on-target:end -->' "$out/section.md" >"$out/pages/perf.1"
splice "$out/pages/perf.1" '<!-- headline-target:begin -->' '<!-- headline-target:end -->' \
  "$out/headline.md" >"$out/pages/perf.2"
stale=0
for page in README.md CHANGELOG.md $(cd "$root" && printf '%s\n' docs/*.md firmware/boards/*/README.md); do
  src=$root/$page
  [ "$page" = docs/performance.md ] && src=$out/pages/perf.2
  spans "$out/figures.tsv" "$src" >"$out/pages/new"
  if ! cmp -s "$out/pages/new" "$root/$page"; then
    if [ "$mode" = write ]; then
      cp "$out/pages/new" "$root/$page"
      echo "wrote $page" >&2
    elif sizes_near "$root/$page" "$out/pages/new"; then
      echo "$page: the image sizes differ by at most 64 B (built in another clone): current" >&2
    else
      diff -u "$root/$page" "$out/pages/new" | head -n 60 >&2 || true
      echo "$page: differs from what this run measured; rerun firmware/image/measure.sh" >&2
      stale=1
    fi
  fi
done
# The racing path's counts, row by row (`--features rows`), to which
# `cargo run --release -p scanvert-bench -- --only race` fits the race's
# cost model (its tests fail when the fit is not this file's): the
# file's header kept, its counts this run's.
rows_file=$image_dir/rows-m4.txt
{
  grep '^#' "$rows_file"
  grep -E '^(prepare|row|tokens|empty|insert) ' "$out/arm-rows.log"
} >"$out/rows-m4.txt"
if ! cmp -s "$out/rows-m4.txt" "$rows_file"; then
  if [ "$mode" = write ]; then
    cp "$out/rows-m4.txt" "$rows_file"
    echo "wrote firmware/image/rows-m4.txt" >&2
  else
    diff -u "$rows_file" "$out/rows-m4.txt" | head -n 30 >&2 || true
    echo "firmware/image/rows-m4.txt: differs from the rows this run counted; rerun firmware/image/measure.sh, then fit the race model again (cargo run --release -p scanvert-bench -- --only race)" >&2
    stale=1
  fi
fi
if [ "$mode" = check ]; then
  if [ "$stale" = 1 ]; then
    exit 1
  fi
  echo "every figure measure.sh owns is current" >&2
fi
