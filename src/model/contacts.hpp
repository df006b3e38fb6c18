// The contact stage: the records of one state's contact pass (contact_law.hpp, contact_pass) and
// the state they are of. Everything that needs contact reads them, as every stage of Box2D v3's
// contact solver reads one constraint array and MuJoCo's sensors read d->contact: the forces and
// the Jacobian (rhs.cpp), LuGre's bristle rates, the integrator's Newton aids and switching
// functions (src/integrate), the observables (observables.hpp).
//
// Who fills them: the right-hand side fills a workspace's records at every state it evaluates
// (rhs.cpp); so does observe() for an observation. A reader at a state (t, y) takes them through
// contacts_at, which fills them only when they are not that state's: the state is compared bit
// for bit with the one they were filled at (its q, v and bristle deflections z, and t). The Drive
// is not compared: a change of it is seen from the next right-hand side, and every integrator
// evaluates one first when it restarts after a change (the Drive changes only then).
#pragma once

#include <vector>

#include "model/contact_law.hpp"
#include "model/drive.hpp"
#include "model/forces.hpp"
#include "model/model.hpp"

namespace beltsim {

struct Workspace;

// The pairs of a contact stage in pass order: the first list's, then the second's. Each list goes
// pulley by pulley, in element order within a pulley, and the second list (the belt's second
// half, elements n/2..n-1, or none) follows the first (elements 0..n/2-1, or all), so the pairs
// of one pulley, taken in this order, are in element order.
class ContactView {
 public:
  ContactView(const ContactList& a, const ContactList& b) : a_(&a), b_(&b) {}
  int size() const { return static_cast<int>(a_->size() + b_->size()); }
  const ContactPair& operator[](int k) const {
    const int na = static_cast<int>(a_->size());
    return k < na ? (*a_)[k] : (*b_)[k - na];
  }
  // walks the first list, then steps from its end to the second's start
  class iterator {
   public:
    iterator(const ContactPair* at, const ContactPair* a_end, const ContactPair* b_begin)
        : at_(at), a_end_(a_end), b_begin_(b_begin) {}
    const ContactPair& operator*() const { return *at_; }
    iterator& operator++() {
      if (++at_ == a_end_) at_ = b_begin_;
      return *this;
    }
    bool operator!=(const iterator& o) const { return at_ != o.at_; }

   private:
    const ContactPair *at_, *a_end_, *b_begin_;
  };
  iterator begin() const {
    const ContactPair *a = a_->data(), *a_end = a + a_->size(), *b = b_->data();
    return iterator(a == a_end ? b : a, a_end, b);
  }
  iterator end() const {
    const ContactPair* b_end = b_->data() + b_->size();
    return iterator(b_end, b_end, b_end);
  }

 private:
  const ContactList *a_, *b_;
};

// The records of one state's contact pass and the state they are of.
class ContactRecords {
 public:
  // one list per half of a belt evaluated in two halves (workspace.hpp, Halves: each half's pass
  // fills its own), else every pair in half[0] and none in half[1]
  ContactList half[2];
  ContactView pairs() const { return ContactView(half[0], half[1]); }
  // true when they are the records of (t, y) with at least the pairs `which` asks for (those of
  // Pairs::all serve a reader of Pairs::touching too: every reader skips the pairs out of contact)
  bool of(const Model& m, double t, const double* y, Pairs which = Pairs::touching) const;
  // marks them as the records of (t, y) (a pass has just filled them with `which`)
  void stamp(const Model& m, double t, const double* y, Pairs which);
  // marks them as nobody's (a pass is about to overwrite them)
  void forget() { stamped_ = false; }

 private:
  bool stamped_ = false;
  Pairs which_ = Pairs::touching;
  double t_ = 0;
  std::vector<double> state_;  // the q and v of the state, then its z: what the pass reads of it
};

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
