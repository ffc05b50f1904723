#pragma once
// What the Newton solver needs of self-contact (contact_newton.cpp; docs/model.md, Newton solver): how far
// back its window reaches, which nodes a contact couples off the band, and each pair's stiffness.
#include "rootsim/contact.hpp"

namespace rootsim {

// the lowest node of the element pairs that self-contact watches (closer than 2R + a skin of R) and whose
// younger element reaches node `from` or beyond (nodes() when there is none): the Newton solver's window
// reaches back to it (docs/model.md, Newton solver: contacts are among the unknowns), so that the old turns
// the window's part of a coil presses on can yield
int firstNodeNearContact(const RodParams& p, const Environment& env, const RodState& s, ContactWorkspace& cw,
                         int from = 0);

// the stiffness of every self-contact pair in contact (gap < 0) into cw.stiffness, by central differences
// of the pair's force with step h [m] (the closest points and the normal move with the nodes). The Newton
// solver takes the rest of its Jacobian from coloured differences without self-contact: a coloured pass
// would read a far partner's response into the rows of its own colour's blocks.
void selfContactStiffness(const RodParams& p, const Environment& env, const RodState& s, double h,
                          ContactWorkspace& cw);

// the stiffness of every contact with another root on a plate (cw.neighbours, pairs in contact) into
// cw.neighbourStiffness, by central differences of neighbourPairForce with step h [m]: the columns of this
// root's two nodes go into its own Jacobian (the coloured passes leave the contact between roots out, as
// self-contact), those of the capsule's ends couple it to the other root in a plate's coupled Newton
// system (relaxNewtonCoupled)
void neighbourContactStiffness(const RodParams& p, const Environment& env, const RodState& s, double h,
                                ContactWorkspace& cw);

// nodes whose self-contact couples them to nodes far along the rod (off the banded pattern of the
// stiffness matrix): cw.contactNode is 1 for both nodes of each element in a self-contact pair (gap < 0),
// 0 elsewhere. Allocates nothing once cw is sized.
void markSelfContactNodes(const RodParams& p, const Environment& env, const RodState& s, ContactWorkspace& cw);

}  // namespace rootsim
