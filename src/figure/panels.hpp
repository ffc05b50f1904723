#pragma once
// The figure panels (docs/model.md, Paper cases), one function each that runs its cases, draws it and
// adds its claims; and the case lists the report runs in one batch before the panels.
#include <string>
#include <vector>

#include "figure_cases.hpp"

namespace rootsim::fig {

// each makes one panel (NAME.png, NAME.svg in c.opt.out) and returns its markdown section
std::string fig2a(const Ctx& c);        // fig2a.cpp
std::string fig2b(const Ctx& c);        // fig2b.cpp
std::string fig2cde(const Ctx& c);      // fig2cde.cpp
std::string fig3a(const Ctx& c);        // fig3ab.cpp
std::string fig3b(const Ctx& c);        // fig3ab.cpp
std::string fig3d(const Ctx& c);        // fig3d.cpp
std::string fig3dGamma1(const Ctx& c);  // fig3d.cpp
std::string fig3dApical(const Ctx& c);  // fig3d.cpp
std::string fig4a(const Ctx& c);        // fig4a.cpp
std::string fig4g(const Ctx& c);        // fig4g.cpp

// Figs. 2B-E (fig2b.cpp): the waving root on the plate, the free organ beside it, and free organs over
// the paper's range of beta (kFreeBetas, Lgz/R = 10), 20 h of growth each, for Eq. 7's exponent
Case wavingCase(const Ctx& c);
Case freeCase(const Ctx& c);
inline const std::vector<double> kFreeBetas = {0.05, 0.1, 0.2, 0.5, 1.0};
std::vector<Case> freeOrgans();
// every run of fig2b and fig2cde, in one batch (so both jobs stay busy)
std::vector<Case> fig2Runs(const Ctx& c);
// the runs of Figs. 3A and 3B over beta and alpha (fig3ab.cpp)
std::vector<Case> scalingCases(const Ctx& c);
// the cells of a phase diagram over alpha and beta Lgz / R (fig3d.cpp)
std::vector<Case> phaseCases(const Ctx& c, double gamma, bool apical);
// the intrinsic twists R tau of Figs. 4A and 4G (fig4a.cpp)
std::vector<double> tauValues(const Ctx& c);

}  // namespace rootsim::fig
