// The contact-state criterion (model/observables.hpp, classify_contact) on arcs written as
// patterns, one character per element in the direction of travel: '0' off the pulleys, '.' inside
// the friction band (|slip| <= Δv), '+'/'-' saturated, slipping forward/backward. The patterns
// are the ones seen on the two-pulley drive (60 and 240 elements): settling at the entry, a
// one-element dip inside the gross-slip arc, the last element lifting off; and on the serpentine
// drive's free idlers (scripts/serpentine.lua), the belt lifting off, its last element or two
// slipping backwards.
#include <gtest/gtest.h>

#include <string>

#include "model/observables.hpp"

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
  double slip = 0, contact = 0;
  classify("00+-+....+++++++.+00", &slip, &contact);
  EXPECT_DOUBLE_EQ(slip, 9 * 0.01);     // elements × pitch
  EXPECT_DOUBLE_EQ(contact, 16 * 0.01);
}

}  // namespace
}  // namespace beltsim
