// The contact stage's records (model/contacts.hpp): they know the state they are of, a reader at
// another state (or at the same pointer after the state moved in place) gets a pass of its own,
// a belt split in two halves gives every pulley the whole belt's pairs in element order, and the
// questions about one pulley or one element read the records that observe() reads.
#include "model/contacts.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "model/jacobian_check.hpp"
#include "model/observables.hpp"
#include "model/rhs.hpp"
#include "support/presets.hpp"

namespace beltsim {
namespace {

using test::running_state;

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

// what the right-hand side leaves in its workspace: the records of (t, y) and of no other state
TEST(Contacts, RecordsKnowTheirState) {
  SceneDef d = presets::paper_dry();
  d.track_energy = true;
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  Eigen::VectorXd y = running_state(sc, 0.1, 30.0, 3);
  Workspace ws(m, false);
  Eigen::VectorXd dy(m.n_state());
  EXPECT_FALSE(ws.contacts.of(m, 0.1, y.data()));
  rhs(m, dr, 0.1, y.data(), dy.data(), &ws);
  EXPECT_TRUE(ws.contacts.of(m, 0.1, y.data()));
  EXPECT_FALSE(ws.contacts.of(m, 0.1, y.data(), Pairs::all));  // the right-hand side keeps the touching pairs
  EXPECT_FALSE(ws.contacts.of(m, std::nextafter(0.1, 1.0), y.data()));
  const int N = m.n_coord();
  Eigen::VectorXd moved = y;
  moved[N + 3 * 7] += 1e-12;  // one element's velocity
  EXPECT_FALSE(ws.contacts.of(m, 0.1, moved.data()));
  moved = y;
  moved[m.pulley_coord(0)] = -moved[m.pulley_coord(0)] + 1;  // a pulley's angle: compared too
  EXPECT_FALSE(ws.contacts.of(m, 0.1, moved.data()));
  moved = y;
  moved[2 * N] += 1.0;  // an energy integral: the pass does not read it
  EXPECT_TRUE(ws.contacts.of(m, 0.1, moved.data()));
  // a reader of every pair fills them again, and they serve a reader of the touching ones
  const ContactRecords& all = contacts_at(m, dr, 0.1, y.data(), ws, Pairs::all);
  EXPECT_EQ(all.pairs().size(), m.n_p() * m.n_el());
  EXPECT_TRUE(ws.contacts.of(m, 0.1, y.data()));
  EXPECT_TRUE(ws.contacts.of(m, 0.1, y.data(), Pairs::all));
}

// The Jacobian reads the right-hand side's records at the same state and takes a pass of its own
// at any other, the same state vector changed in place included: its blocks have the bits of a
// Jacobian evaluated alone.
TEST(Contacts, JacobianReadsOnlyItsStatesRecords) {
  const Scene sc = build_scene(presets::paper_dry());
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  Eigen::VectorXd y = running_state(sc, 0.1, 30.0, 3);
  Workspace ws(m, false);
  Eigen::VectorXd dy(m.n_state());
  Jacobian J, Jref;
  J.resize(m), Jref.resize(m);
  auto expect_alone = [&](const Eigen::VectorXd& at) {
    jacobian(m, dr, 0.1, at.data(), J, &ws);
    jacobian(m, dr, 0.1, at.data(), Jref);
    EXPECT_TRUE(same_bits(J.K.to_dense(), Jref.K.to_dense()));
    EXPECT_TRUE(same_bits(J.C.to_dense(), Jref.C.to_dense()));
    EXPECT_TRUE(same_bits(J.f_t, Jref.f_t));
  };
  rhs(m, dr, 0.1, y.data(), dy.data(), &ws);
  expect_alone(y);  // the right-hand side's records
  // every element moved in place, out of the pulleys' contact circles or deeper in
  for (int i = 0; i < m.n_el(); ++i) y[3 * i + 1] *= 1.001;
  EXPECT_FALSE(ws.contacts.of(m, 0.1, y.data()));
  expect_alone(y);
  EXPECT_TRUE(ws.contacts.of(m, 0.1, y.data()));  // the Jacobian's own pass, kept
}

// LuGre's bristle deflections are part of the state the records are of
TEST(Contacts, BristlesArePartOfTheState) {
  SceneDef d = presets::paper_dry();
  d.friction.law = FrictionKind::lugre;
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  ASSERT_GT(m.n_bristle(), 0);
  Eigen::VectorXd y = running_state(sc, 0.1, 30.0, 3);
  Workspace ws(m, false);
  fill_contacts(m, sc.drive, 0.1, y.data(), ws);
  EXPECT_TRUE(ws.contacts.of(m, 0.1, y.data()));
  y[m.bristle_offset() + 5] += 1e-9;
  EXPECT_FALSE(ws.contacts.of(m, 0.1, y.data()));
}

// A long belt's records, filled per half (the right-hand side's pass, or a reader's), read in
// pass order: every pulley's pairs in element order, the same pairs as one pass over the belt.
TEST(Contacts, HalvesReadAsOnePass) {
  SceneDef d = presets::paper_dry();
  d.belt.elements = 600;
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const Eigen::VectorXd y = running_state(sc, 0.1, 30.0, 6);
  Workspace halves(m);
  ASSERT_TRUE(halves.halves);
  ContactRecords one;
  for (const Pairs which : {Pairs::touching, Pairs::all}) {
    fill_contacts(m, dr, 0.1, y.data(), one, which);
    fill_contacts(m, dr, 0.1, y.data(), halves, which);
    ASSERT_FALSE(halves.contacts.half[1].empty());
    const ContactView a = one.pairs(), b = halves.contacts.pairs();
    ASSERT_EQ(a.size(), b.size());
    for (int j = 0; j < m.n_p(); ++j) {
      int k = 0, l = 0;
      for (;; ++k, ++l) {
        while (k < a.size() && a[k].j != j) ++k;
        while (l < b.size() && b[l].j != j) ++l;
        if (k == a.size() || l == b.size()) break;
        ASSERT_EQ(a[k].i, b[l].i);
        ASSERT_EQ(std::memcmp(&a[k].nl.N, &b[l].nl.N, sizeof(double)), 0);
        ASSERT_EQ(std::memcmp(&a[k].fl.mu_eff, &b[l].fl.mu_eff, sizeof(double)), 0);
      }
      EXPECT_EQ(k == a.size(), l == b.size()) << "pulley " << j;
    }
  }
}

// one fill of a state's records answers every question about its pulleys and elements with the
// bits observe() gives
TEST(Contacts, QuestionsAboutOnePulleyReadTheRecords) {
  auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (const SceneDef& d : {presets::paper_dry(), presets::automotive_tensioner()}) {
    const Scene sc = build_scene(d);
    const Model& m = sc.model;
    const Drive& dr = sc.drive;
    const Eigen::VectorXd y = running_state(sc, 0.1, 30.0, 3);
    Observation o;
    observe(m, dr, sc.senses(), 0.1, y.data(), o);
    ContactRecords c;
    fill_contacts(m, dr, 0.1, y.data(), c);
    std::vector<PulleyObs> all;
    ContactRecords scratch;
    observe_pulleys(m, dr, 0.1, y.data(), scratch, all);
    EXPECT_TRUE(scratch.of(m, 0.1, y.data()));
    for (int j = 0; j < m.n_p(); ++j) {
      const PulleyObs p = observe_pulley(m, dr, 0.1, y.data(), c, j);
      Vec2 hub;
      const double torque = belt_torque(c, j, &hub);
      EXPECT_TRUE(same(p.belt_torque, o.pulleys[j].belt_torque) && same(torque, p.belt_torque)) << j;
      EXPECT_TRUE(same(p.hub_load, o.pulleys[j].hub_load) && same(hub.x(), p.hub.x()) && same(hub.y(), p.hub.y()));
      EXPECT_TRUE(same(p.torque, o.pulleys[j].torque) && same(all[j].torque, p.torque)) << j;
      EXPECT_TRUE(same(all[j].belt_torque, p.belt_torque)) << j;
    }
    int touching = 0;
    for (int i = 0; i < m.n_el(); ++i) {
      const ElementContact e = element_contact(c, i);
      EXPECT_EQ(e.pulley, o.elements[i].pulley) << i;
      EXPECT_TRUE(same(e.normal, o.elements[i].normal)) << i;
      EXPECT_TRUE(same(e.slip, o.contact[i].slip) && same(e.friction, o.contact[i].friction)) << i;
      touching += e.pulley >= 0;
    }
    EXPECT_GT(touching, 10);
  }
}

}  // namespace
}  // namespace beltsim
