// The contact-state criterion (model/observables.hpp, classify_contact) on arcs written as
// patterns, one character per element in the direction of travel: '0' off the pulleys, '.' inside
// the friction band (|slip| <= Δv), '+'/'-' saturated, slipping forward/backward. The patterns
// are the ones seen on the two-pulley drive (60 and 240 elements): settling at the entry, a
// one-element dip inside the gross-slip arc, the last element lifting off; and on the serpentine
// drive's free idlers (scripts/serpentine.lua), the belt lifting off, its last element or two
// slipping backwards.
#include "model/observables.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace beltsim {
namespace {

// the state of each element after classify_contact: '0' free, 's' stick, 'S' slip; and the arcs
std::string classify(const std::string& pattern, double* slip_arc = nullptr, double* contact_arc = nullptr,
                     double belt_speed = 6, double penetration = 0) {
  Model m;
  m.friction.dv = 1e-5;
  m.belt.pitch = 0.01;
  m.pulleys.resize(1);
  m.pulleys[0].radius = 0.1;  // a lift-off zone sqrt(2·R·p) long: of one element of 0.01 m up to p = 5e-4 m
  Observation o;
  o.pulleys.resize(1);
  o.belt_speed = belt_speed;
  o.elements.resize(pattern.size());
  for (size_t i = 0; i < pattern.size(); ++i) {
    ElementObs& e = o.elements[i];
    const char c = pattern[i];
    e.pulley = c == '0' ? -1 : 0;
    e.state = c == '0' ? ContactState::free : ContactState::slip;  // whatever it was before
    e.slip = c == '+' ? 3e-4 : c == '-' ? -3e-4 : c == '.' ? 0.5e-5 : 0.0;
    e.penetration = c == '0' ? 0.0 : penetration;
  }
  classify_contact(m, o);
  std::string out;
  for (const ElementObs& e : o.elements)
    out += e.state == ContactState::free ? '0' : e.state == ContactState::slip ? 'S' : 's';
  if (slip_arc) *slip_arc = o.pulleys[0].slip_arc;
  if (contact_arc) *contact_arc = o.pulleys[0].contact_arc;
  return out;
}

TEST(ContactState, GrossSlipIsTheSaturatedRunBeforeTheExit) {
  // 60 elements, driven pulley: settling at the entry, a dip in the arc, the exit saturated
  EXPECT_EQ(classify("00+-+....+++++++.+00"), "00sssssssSSSSSSSSS00");
  // micro-slip in the band everywhere: all sticking (|F| >= 0.98·μN would call some slipping)
  EXPECT_EQ(classify("00........00"), "00ssssssss00");
  // the last element lifting off inside the band sticks and does not end the arc
  EXPECT_EQ(classify("0....-----.0"), "0ssssSSSSSs0");
  // settling at the entry alone is no gross slip
  EXPECT_EQ(classify("0-++.--......0"), "0ssssssssssss0");
  // two elements inside the band end the arc; so does saturation the other way
  EXPECT_EQ(classify("0+++..+++0"), "0sssssSSS0");
  EXPECT_EQ(classify("0+++.-.---0"), "0ssssSSSSS0");
  // the arc may run across element n-1 → 0 (the belt is a ring)
  EXPECT_EQ(classify("+++0000..."), "SSS0000sss");
  // a drive running backwards: the belt leaves the pulley at the lowest element number
  EXPECT_EQ(classify("0+.++++...-+-0", nullptr, nullptr, -6), "0SSSSSSssssss0");
  // the last element slipping backwards alone is lifting off (its path's geometry, in a lift-off
  // zone of one element here), and no run starts there; behind it one may (a driven pulley's arc),
  // and forwards alone it is one
  EXPECT_EQ(classify("0.....-0"), "0ssssss0");
  EXPECT_EQ(classify("0....+-0"), "0ssssSs0");
  EXPECT_EQ(classify("0.....+0"), "0sssssS0");
  EXPECT_EQ(classify("0....--0"), "0ssssSS0");
  EXPECT_EQ(classify("0...-.-0"), "0sssSSS0");  // backwards, but with the one before it across a dip
  EXPECT_EQ(classify("0-.....000", nullptr, nullptr, -6), "0ssssss000");
  // a deeper contact (p = 1e-3 m: a zone of sqrt(2·0.1·1e-3) = 0.014 m, two elements) lifts two off
  EXPECT_EQ(classify("0.....--0", nullptr, nullptr, 6, 1e-3), "0sssssss0");
  EXPECT_EQ(classify("0....+--0", nullptr, nullptr, 6, 1e-3), "0ssssSss0");
  EXPECT_EQ(classify("0....---0", nullptr, nullptr, 6, 1e-3), "0ssssSSS0");
  // the last element lifting off backwards and the one behind it inside the band: the run behind
  // them is the gross-slip arc (a 480-element driven pulley read no slip arc at 66 of 151 samples)
  EXPECT_EQ(classify("0....++++.-0"), "0ssssSSSSss0");
  // elsewhere on the arc a run longer than the settling (three elements here) in the gross-slip
  // arc's direction slips: a wet stretch arriving on a driver (a user's 15 elements at the entry)
  EXPECT_EQ(classify("0-----....------0"), "0SSSSSssssSSSSSS0");
  EXPECT_EQ(classify("0---....----0"), "0sssssssSSSS0");          // three: settling
  EXPECT_EQ(classify("0+++++....------0"), "0sssssssssSSSSSS0");  // the other way: the overshoot settling
  EXPECT_EQ(classify("0..-----....0"), "0ssSSSSSssss0");          // no gross-slip arc: either way
  double slip = 0, contact = 0;
  classify("00+-+....+++++++.+00", &slip, &contact);
  EXPECT_DOUBLE_EQ(slip, 9 * 0.01);     // elements × pitch
  EXPECT_DOUBLE_EQ(contact, 16 * 0.01);
}

// The belt's speed on a wrap and the creep against it (wrap_speeds), worked by hand: one pulley
// (R = 0.1 m, ω = 60 rad/s, the belt going round it anticlockwise), elements given as slip [m/s]
// and penetration [m], classified first as observe() does.
struct Wrap {
  Model m;
  Observation o;
  Wrap(const std::vector<double>& slip, const std::vector<double>& depth, double omega = 60) {
    m.friction.dv = 1e-5;
    m.belt.pitch = 0.01;
    m.pulleys.resize(1);
    m.pulleys[0].radius = 0.1;
    o.belt_speed = 6;
    o.pulleys.resize(1);
    o.pulleys[0].omega = omega;
    o.elements.resize(slip.size() + 2);  // one free element either side
    for (size_t i = 0; i < slip.size(); ++i) {
      ElementObs& e = o.elements[i + 1];
      e.pulley = 0, e.state = ContactState::stick, e.slip = slip[i], e.penetration = depth[i];
    }
    classify_contact(m, o);
    wrap_speeds(m, {1}, o);
  }
};

TEST(WrapSpeeds, TheAdhesionArcAtThePitchLineTheSlipArcAtItsOwnSpeed) {
  // settling at the entry (saturated, sticking), micro-slip, a gross-slip arc of two at the exit;
  // the first and last elements partly lifted off (penetration 1e-4 against 2e-4 inside)
  const Wrap w({-3e-3, 5e-6, -4e-6, 2e-6, 3e-3, 5e-3}, {1e-4, 2e-4, 2e-4, 2e-4, 2e-4, 1e-4});
  const PulleyObs& p = w.o.pulleys[0];
  const double v_pitch = 60 * (0.1 - 2e-4), v_rim = 60 * 0.1;  // p̄ of the four inner elements
  const double v_belt = v_pitch + (3e-3 + 5e-3) / 6;           // the slip arc's slip over all six
  EXPECT_DOUBLE_EQ(p.slip_arc, 0.02);
  EXPECT_DOUBLE_EQ(p.belt_speed, v_belt);
  EXPECT_DOUBLE_EQ(p.slip_speed, v_belt - v_rim);
  EXPECT_DOUBLE_EQ(p.creep, 1 - v_rim / v_belt);
  EXPECT_DOUBLE_EQ(p.creep_pitch, 1 - v_pitch / v_belt);
  EXPECT_DOUBLE_EQ(p.slip_pitch, (3e-3 + 5e-3) / 6);  // the header's slip: no radial part
  EXPECT_GT(p.slip_pitch, 0);
  EXPECT_GT(p.creep_pitch, 0);  // driven: the belt leaves faster than the rim
  EXPECT_LT(p.creep, 0);        // its radial part, -p̄/R = -2e-3, outweighs the creep
}

TEST(WrapSpeeds, AWrapWithoutGrossSlipReadsNoCreep) {
  // a free idler: micro-slip, and the last element slipping backwards alone as it lifts off
  const Wrap w({4e-6, -6e-6, 3e-6, -0.04}, {1.5e-4, 2e-4, 2.2e-4, 0.2e-4}, 200);
  const PulleyObs& p = w.o.pulleys[0];
  EXPECT_DOUBLE_EQ(p.slip_arc, 0);
  EXPECT_EQ(p.creep_pitch, 0);
  EXPECT_EQ(p.slip_pitch, 0);
  EXPECT_NEAR(p.slip_speed, -200 * 2.1e-4, 1e-12);  // the radial part alone: -ω·p̄ of the inner two
  EXPECT_DOUBLE_EQ(p.belt_speed, 200 * (0.1 - 2.1e-4));
}

TEST(WrapSpeeds, AWrapNoElementTouchesReadsNaN) {
  const Wrap w({}, {});
  const PulleyObs& p = w.o.pulleys[0];
  EXPECT_TRUE(std::isnan(p.belt_speed) && std::isnan(p.slip_speed) && std::isnan(p.creep) &&
              std::isnan(p.creep_pitch) && std::isnan(p.slip_pitch));
  // a driver: the slip arc backwards; a wrap of two elements takes both for p̄
  const Wrap d({1e-6, -2e-3, -4e-3}, {2e-4, 2e-4, 1e-4});
  EXPECT_LT(d.o.pulleys[0].creep_pitch, 0);
  EXPECT_LT(d.o.pulleys[0].slip_pitch, 0);
  const Wrap two({1e-6, 2e-6}, {1e-4, 3e-4});
  EXPECT_DOUBLE_EQ(two.o.pulleys[0].belt_speed, 60 * (0.1 - 2e-4));
}

}  // namespace
}  // namespace beltsim
