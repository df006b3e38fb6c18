// The render tests' fixture: a 640x360 frame of the paper's half-wet drive set in motion
// (render_scenes.hpp) with the font, and scenes built in a test (a pulley, the serpentine's layout).
#pragma once

#include <gtest/gtest.h>

#include "render/draw_list.hpp"
#include "render/render_scenes.hpp"
#include "render/text.hpp"

namespace beltsim::render::test_frames {

// a pulley of a scene built in a test
inline PulleyDef pulley(const char* name, Vec2 c, double r, WrapSide w) {
  PulleyDef p;
  p.name = name, p.centre = c, p.radius = r, p.wrap = w;
  return p;
}

// scripts/serpentine.lua's six pulleys (without its arm and rotor) and its 200-element belt
inline SceneDef serpentine_layout() {
  SceneDef d;
  d.pulleys = {pulley("crankshaft", {0.09, -0.27}, 0.08, WrapSide::inside),
               pulley("tensioner", {0.015, -0.12}, 0.031, WrapSide::back),
               pulley("alternator", {0, 0}, 0.027, WrapSide::inside),
               pulley("idler", {0.08, 0.01}, 0.03, WrapSide::back),
               pulley("pump", {0.16, -0.06}, 0.056, WrapSide::inside),
               pulley("compressor", {0.24, -0.21}, 0.06, WrapSide::inside)};
  d.belt.elements = 200;
  d.belt.pretension = 300;
  d.belt.loop_sense = -1;
  return d;
}

// the same with the tensioner on its arm (scripts/serpentine.lua's pivot, inertia and spring)
inline SceneDef serpentine_with_arm() {
  SceneDef d = serpentine_layout();
  d.pulleys[1].tensioner = TensionerDef{};
  d.pulleys[1].tensioner->pivot = {0.075, -0.14};
  d.pulleys[1].tensioner->inertia = 1e-3, d.pulleys[1].tensioner->stiffness = 30;
  return d;
}

struct Fixture : ::testing::Test {
  static const Scene& wet() {
    static const Scene sc = test::moving_scene(presets::paper_wet());
    return sc;
  }
  Font font;
  FrameSettings fs() const {
    FrameSettings f;
    f.width = 640, f.height = 360;
    f.png_dir = "x";
    return f;
  }
};

}  // namespace beltsim::render::test_frames
