// The contact stage: the records of one state's contact pass (contact_law.hpp, contact_pass) and
// the state they are of (contact_records.hpp). Everything that needs contact reads them, as every
// stage of Box2D v3's contact solver reads one constraint array and MuJoCo's sensors read
// d->contact: the forces and the Jacobian (rhs.cpp), LuGre's bristle rates, the integrator's
// Newton aids and switching functions (src/integrate), the observables (observables.hpp).
//
// Who fills them: the right-hand side fills a workspace's records at every state it evaluates
// (rhs.cpp); so does observe() for an observation. A reader at a state (t, y) takes them through
// contacts_at, which fills them only when they are not that state's: the state is compared bit
// for bit with the one they were filled at (its q, v and bristle deflections z, and t). The Drive
// is not compared: a change of it is seen from the next right-hand side, and every integrator
// evaluates one first when it restarts after a change (the Drive changes only then).
#pragma once

#include "model/contact_law.hpp"
#include "model/contact_records.hpp"
#include "model/drive.hpp"
#include "model/forces.hpp"
#include "model/model.hpp"

namespace beltsim {

struct Workspace;

// The contact stage at (t, y) (y = [q | v | e | z]): fills r with the pass over every element
// (half[1] left empty) and stamps them
void fill_contacts(const Model& m, const Drive& d, double t, const double* y, ContactRecords& r,
                   Pairs which = Pairs::touching);
// the same into w.contacts: a pass per half when w evaluates the belt in two halves (the two at
// once, on its two threads), else one
void fill_contacts(const Model& m, const Drive& d, double t, const double* y, Workspace& w,
                   Pairs which = Pairs::touching);
// a reader's way in: the records of (t, y), w's own when they are that state's (ContactRecords::of),
// else filled first
const ContactRecords& contacts_at(const Model& m, const Drive& d, double t, const double* y, Workspace& w,
                                  Pairs which = Pairs::touching);

}  // namespace beltsim
