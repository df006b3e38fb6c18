#!/usr/bin/env bash
# Rebuilds the pictures of media/ from the paper's three scripts, after building
# (`bash scripts/setup.sh build`); idempotent (the same code gives the same files).
#
#   bash media/make_media.sh          everything (about nine minutes)
#   bash media/make_media.sh paper    only the paper's figures, media/paper/figNN.png, and the
#                                     measured values in docs/paper.md (about a minute)
#
# The paper's figures: each script is run once, then `beltsim plot` draws the columns of one paper
# figure per PNG, and media/paper_values.py measures the points docs/paper.md compares with the
# paper and rewrites that page's generated tables.
# The other pictures: the main runs' own frames give the tension (dry) and friction (half-wet)
# pictures; two variants of the scripts, with their frames block replaced, give a normal-force and
# a slip-velocity picture (t_start = t_end: a single frame).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
b=${BELTSIM:-build/beltsim}
what=${1:-all}
case "$what" in
  all|paper) ;;
  *) echo "usage: bash media/make_media.sh [all|paper]" >&2; exit 2 ;;
esac
[ -x "$b" ] || { echo "make_media: $b not found: build first (bash scripts/setup.sh build)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
export BELTSIM_TERM_IMAGES=off

# the three runs (the out folders are named after the scripts: the plots' titles name the run)
frames=()
[ "$what" = paper ] && frames=(--no-frames)
for s in paper_dry paper_wet automotive_wet; do
  "$b" run "scripts/$s.lua" --out "$tmp/$s" "${frames[@]}" >/dev/null
done

# --- the paper's figures: one PNG per figure, the quantities its caption names -------------------
mkdir -p media/paper
fig() {  # figure number, run, columns...
  local n=$1 run=$2
  shift 2
  "$b" plot "$tmp/$run/timeseries.csv" "$@" --out "media/paper/fig$n.png" >/dev/null
}
# dry belt (§3, Figs 8-13)
fig 08 paper_dry driver.omega driven.omega
fig 09 paper_dry driver.torque driven.torque
fig 10 paper_dry probe.sde_force
fig 11 paper_dry probe.normal_force
fig 12 paper_dry probe.friction_force
fig 13 paper_dry probe.slip_velocity
# half of the belt wet (§3, Figs 15-18)
fig 15 paper_wet driver.omega driven.omega
fig 16 paper_wet driver.torque driven.torque
fig 17 paper_wet probe.friction_force
fig 18 paper_wet probe.slip_velocity
# the automotive drive, 30 % wet (§4, Figs 20-23)
fig 20 automotive_wet crankshaft.omega alternator.omega pump.omega tensioner.omega
fig 21 automotive_wet crankshaft.torque alternator.torque pump.torque tensioner.torque
fig 22 automotive_wet probe.friction_force
fig 23 automotive_wet probe.sde_force
python3 media/paper_values.py "$tmp" docs/paper.md

if [ "$what" = all ]; then
  # docs/automotive.md: the idler on its tensioner arm and held fixed
  "$b" run scripts/automotive_tensioner.lua --out "$tmp/automotive_tensioner" >/dev/null
  "$b" run scripts/automotive_tensioner.lua --set idler=fixed --out "$tmp/automotive_tensioner_fixed" >/dev/null
  "$b" plot "$tmp/automotive_tensioner/timeseries.csv" tensioner.arm_angle span_crankshaft_tensioner.tension \
    span_pump_crankshaft.tension --from 0.3 --out media/automotive_tensioner_arm.png >/dev/null
  "$b" plot "$tmp/automotive_tensioner_fixed/timeseries.csv" span_crankshaft_tensioner.tension \
    span_pump_crankshaft.tension --from 0.3 --out media/automotive_tensioner_fixed.png >/dev/null
  # docs/automotive.md: the alternator's rotor behind a one-way and a two-way decoupler
  for k in one_way two_way; do
    "$b" run scripts/automotive_decoupler.lua --set coupling=$k --no-frames --out "$tmp/decoupler_$k" >/dev/null
    "$b" plot "$tmp/decoupler_$k/timeseries.csv" alternator.omega alternator.rotor_speed alternator.coupling_torque \
      --from 0.3 --out "media/automotive_decoupler_$k.png" >/dev/null
  done
  # docs/modes.md: the automotive drive's Campbell diagram (about two minutes)
  "$b" modes scripts/automotive_tensioner.lua --campbell crankshaft --rpm 800:3200:4 --orders 2,4 \
    --out "$tmp/campbell" >/dev/null
  cp "$tmp/campbell/campbell.png" media/campbell_automotive.png
  # docs/tutorial.md: a frame of the tutorial's run, and its console session's sim:show
  "$b" run docs/examples/tutorial/drive.lua --out "$tmp/tutorial" >/dev/null
  cp "$tmp/tutorial/frames/frame_00075.png" media/tutorial_drive.png
  grep '^> ' docs/tutorial.md | cut -c3- |
    "$b" console docs/examples/tutorial/drive.lua --set live=true --out "$tmp/tutorial_live" >/dev/null
  cp "$tmp/tutorial_live/show_0.100000.png" media/tutorial_console_slip.png
  # docs/console.md: its session's sim:show and sim:plot
  grep '^> ' docs/console.md | cut -c3- |
    BELTSIM_TERM_IMAGES=off "$b" console scripts/live_dry.lua --out "$tmp/live_dry" >/dev/null
  cp "$tmp/live_dry/show_0.750000.png" media/console_show.png
  cp "$tmp/live_dry/plot_0.750000.png" media/console_plot.png
  cp "$tmp/paper_dry/frames/frame_00300.png" media/dry_tension_1.0s.png
  cp "$tmp/paper_wet/frames/frame_00180.png" media/wet_friction_0.6s.png
  cp "$tmp/paper_wet/frames/frame_00090.png" media/wet_friction_0.3s.png
  cp "$tmp/automotive_wet/frames/frame_00150.png" media/automotive_slip_0.5s.png
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
  # 640x360, and the same as a GIF (docs/frames-and-video.md shows it inline)
  ffmpeg -v error -y -ss 1.5 -t 3 -i "$tmp/paper_wet/paper_wet.mp4" -vf scale=640:360 -c:v libx264 -preset slow \
    -crf 28 -pix_fmt yuv420p -colorspace bt709 -color_primaries bt709 -color_trc bt709 -movflags +faststart \
    media/wet_clip.mp4
  ffmpeg -v error -y -i media/wet_clip.mp4 \
    -vf "fps=10,scale=480:-1:flags=lanczos,split[a][b];[a]palettegen=max_colors=64[p];[b][p]paletteuse=dither=none" \
    media/wet_clip.gif
  # docs/friction.md: the half-wet drive under each friction law, the speeds of both runs in one
  # plot (their timeseries.csv share the sample times; the columns take the law's name in front)
  for law in threlfall stribeck lugre; do
    "$b" run scripts/paper_wet.lua --set friction=$law --no-frames --out "$tmp/wet_$law" >/dev/null
  done
  mkdir -p "$tmp/friction_laws"
  python3 media/merge_runs.py "$tmp/friction_laws/timeseries.csv" threlfall="$tmp/wet_threlfall/timeseries.csv" \
    stribeck="$tmp/wet_stribeck/timeseries.csv" lugre="$tmp/wet_lugre/timeseries.csv"
  "$b" plot "$tmp/friction_laws/timeseries.csv" threlfall.driven.omega stribeck.driven.omega lugre.driven.omega \
    --out media/friction_laws_wet.png >/dev/null
fi
ls -la media media/paper
