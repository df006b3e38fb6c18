// The records of one state's contact pass and the state they are of, as plain data (the contact
// stage that fills and reads them: model/contacts.hpp). A workspace holds them (model/workspace.hpp),
// so does an observation (model/observables.hpp).
#pragma once

#include <vector>

#include "model/contact_law.hpp"
#include "model/model.hpp"

namespace beltsim {

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

}  // namespace beltsim
