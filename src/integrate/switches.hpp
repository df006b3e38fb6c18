// Switching functions of the belt's contact and friction laws, for integrators that locate the
// kinks of the right-hand side and restart there (the CVODE peer's rootfinding, CVodeRootInit).
// Each element–pulley pair has kSwitchesPerPair continuous functions of the state whose zeros are
// the pair's kinks (derivation at the top of switches.cpp).
#pragma once

#include "model/contacts.hpp"
#include "model/model.hpp"

namespace beltsim {

constexpr int kSwitchesPerPair = 4;
// the number of switching functions of the model: kSwitchesPerPair per element and pulley
int switch_count(const Model& m);
// g[kSwitchesPerPair·(j·n + i) + k] for pulley j, element i, from the contact records of a state
// with every pair (model/contacts.hpp, Pairs::all)
void contact_switches(const Model& m, const ContactView& pairs, double* g);

}  // namespace beltsim
