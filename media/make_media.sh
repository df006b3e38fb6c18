#!/usr/bin/env bash
# Rebuilds the pictures of media/ from the paper's scripts (run from the repository root after
# building; about five minutes). The main runs' own frames give the tension (dry) and friction
# (half-wet) pictures; two variants of the scripts, with their frames block replaced, give a
# normal-force and a slip-velocity picture (t_start = t_end: a single frame).
set -euo pipefail
b=${BELTSIM:-build/beltsim}
tmp=$(mktemp -d)
"$b" run scripts/paper_dry.lua --out "$tmp/dry" >/dev/null
"$b" run scripts/paper_wet.lua --out "$tmp/wet" >/dev/null
cp "$tmp/dry/frames/frame_00300.png" media/dry_tension_1.0s.png
cp "$tmp/wet/frames/frame_00180.png" media/wet_friction_0.6s.png
cp "$tmp/wet/frames/frame_00090.png" media/wet_friction_0.3s.png
"$b" run scripts/automotive_wet.lua --out "$tmp/auto" >/dev/null
cp "$tmp/auto/frames/frame_00150.png" media/automotive_slip_0.5s.png
variant() {  # script, out, frames table
  awk -v f="$3" '/^  frames = \{/ {skip = 1; print "  frames = " f ","; next}
                 skip && /^  \},/ {skip = 0; next} !skip' "$1" > "$tmp/variant.lua"
  "$b" run "$tmp/variant.lua" --out "$2" >/dev/null
}
variant scripts/paper_dry.lua "$tmp/dryn" \
  '{ t_start = 1.0, size = {1280, 720}, quantity = "normal", range = {0, 250}, magnify = 10, png = true }'
cp "$tmp/dryn/frames/frame_00000.png" media/dry_normal_1.0s.png
variant scripts/paper_wet.lua "$tmp/wets" \
  '{ t_start = 0.6, size = {1280, 720}, quantity = "slip", range = {-5, 5}, magnify = 10, png = true }'
cp "$tmp/wets/frames/frame_00000.png" media/wet_slip_0.6s.png
# a short clip: the half-wet run from 0.15 to 0.45 s of simulated time (video 1.5 to 4.5 s),
# 640x360, and the same as a GIF (the README shows it inline)
ffmpeg -v error -y -ss 1.5 -t 3 -i "$tmp/wet/paper_wet.mp4" -vf scale=640:360 -c:v libx264 -preset slow -crf 28 \
  -pix_fmt yuv420p -colorspace bt709 -color_primaries bt709 -color_trc bt709 -movflags +faststart media/wet_clip.mp4
ffmpeg -v error -y -i media/wet_clip.mp4 \
  -vf "fps=10,scale=480:-1:flags=lanczos,split[a][b];[a]palettegen=max_colors=64[p];[b][p]paletteuse=dither=none" \
  media/wet_clip.gif
rm -rf "$tmp"
ls -la media
