// Validity notes of the closed-form force laws: see lub/bearing/law_validity.hpp.
#include "lub/bearing/law_validity.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "lub/bearing/film_force.hpp"
#include "lub/bearing/reynolds.hpp"

namespace lub {

bool is_short_bearing_law(ForceLaw law) { return law == ForceLaw::frene_short || law == ForceLaw::gumbel_short; }

bool is_long_bearing_law(ForceLaw law) {
  return law == ForceLaw::frene_long || law == ForceLaw::gumbel_long || law == ForceLaw::pinkus_sternlicht ||
         law == ForceLaw::pinkus_sternlicht_continuous;
}

bool is_full_film_law(ForceLaw law) { return law == ForceLaw::frene_long || law == ForceLaw::frene_short; }

LawDeviation deviation_from_finite_bearing(ForceLaw law, const BearingGeometry& g) {
  FiniteBearingOptions o;
  o.cavitation = is_full_film_law(law)                                               ? Cavitation::sommerfeld
                 : law == ForceLaw::gumbel_long || law == ForceLaw::gumbel_short ? Cavitation::gumbel
                                                                                  : Cavitation::reynolds;
  FiniteBearingSolver finite(o);
  LawDeviation d{1e300, 0.0};
  for (const double eps : {0.3, 0.6, 0.9})
    for (const bool steady : {true, false}) {
      BearingState s;
      s.eps = eps;
      s.eps_dot = steady ? 0.0 : 1.0;
      s.wedge = steady ? 1.0 : 0.0;
      const FilmForce f = film_force(law, g, 1.0, s, nullptr);
      const FilmForce r = finite.solve(g, 1.0, s);
      const double ratio = std::hypot(f.radial_N, f.tangential_N) / std::hypot(r.radial_N, r.tangential_N);
      if (!std::isfinite(ratio)) continue;
      d.lo = std::min(d.lo, ratio);
      d.hi = std::max(d.hi, ratio);
    }
  return d;
}

std::optional<std::string> geometry_validity_note(const std::string& where, ForceLaw law, const BearingGeometry& g) {
  const double ld = g.length_m / (2.0 * g.journal_radius_m);
  const bool short_out = is_short_bearing_law(law) && ld > kShortBearingMaxLD;
  const bool long_out = is_long_bearing_law(law) && ld < kLongBearingMinLD;
  if (!short_out && !long_out) return std::nullopt;
  // The ratio depends on ε and L/D alone (the clearance and the radius scale out): measured
  // at L/D to two digits, so that the scenes of a study that differ in clearance share a note.
  char lds[32];
  std::snprintf(lds, sizeof lds, "%.2g", ld);
  const double ld2 = std::strtod(lds, nullptr);
  const LawDeviation d = deviation_from_finite_bearing(law, BearingGeometry{1.0, 1.001, 2.0 * ld2});
  char buf[256];
  std::snprintf(buf, sizeof buf,
                " is a %s-bearing law (it assumes L/D %s %g) at L/D = %s: its film force is %.2g-%.2g times the "
                "finite bearing's there",
                short_out ? "short" : "long", short_out ? "<=" : ">=",
                short_out ? kShortBearingMaxLD : kLongBearingMinLD, lds, d.lo, d.hi);
  return where + " = \"" + std::string(name_of(law)) + "\"" + buf +
         " (eps 0.3-0.9, steady and squeeze; finite_reynolds is the reference)";
}

std::string reversing_load_note(const std::string& where, ForceLaw law) {
  return where + ": the load on a full-film law (\"" + std::string(name_of(law)) +
         "\") reverses in the run: the law's sub-ambient half film holds the journal where a real film "
         "ruptures (a cavitated law, gumbel_* or finite_reynolds, does not)";
}

}  // namespace lub
