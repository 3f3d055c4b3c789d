// Where a closed-form force law's assumptions hold, and how far the law is from the finite
// bearing where they do not (docs/theory/force-laws.md, "Validity notes").
//
// - Short-bearing laws (frene_short, gumbel_short) drop the circumferential pressure flow:
//   they assume L/D ≲ 1/2 and overestimate the force more and more above it.
// - Long-bearing laws (frene_long, gumbel_long, pinkus_sternlicht, pinkus_sternlicht_continuous)
//   drop the axial flow: they assume L/D ≳ 2.
// - Full-film laws (frene_long, frene_short) keep the film's sub-ambient half: under a load
//   that reverses, that tension holds the journal where a real film ruptures.
//
// The deviation is measured at the scene's geometry: |F_law| / |F_finite| over ε ∈ {0.3, 0.6,
// 0.9} for a steady load (ε̇ = 0) and a squeeze towards the wall (no rotation), the finite
// bearing (finite_reynolds, 48 × 8, ambient ends) with the cavitation the law assumes (full film
// for Frêne, Gümbel for Gümbel, Reynolds for Pinkus–Sternlicht). The laws are linear in the
// viscosity and the speeds, so the ratio depends on ε and the geometry alone.
#pragma once

#include <optional>
#include <string>

#include "lub/bearing/force_laws.hpp"

namespace lub {

/// Lower and upper bound of |F_law| / |F_finite| over the states above.
struct LawDeviation {
  double lo = 0.0, hi = 0.0;
};

/// Whether `law` assumes a short or a long bearing; false for finite_reynolds.
bool is_short_bearing_law(ForceLaw law);
bool is_long_bearing_law(ForceLaw law);
/// Whether `law` keeps the whole film, sub-ambient pressures included (the Frêne laws).
bool is_full_film_law(ForceLaw law);

/// L/D below which a short-bearing law holds, above which a long-bearing law does.
inline constexpr double kShortBearingMaxLD = 0.5;
inline constexpr double kLongBearingMinLD = 2.0;

LawDeviation deviation_from_finite_bearing(ForceLaw law, const BearingGeometry& g);

/// A note when `law` is used at a length-to-diameter ratio outside its assumption, naming
/// `where` (the JSON Pointer of the force law), the L/D and the deviation measured at the L/D
/// rounded to two digits; nullopt inside it.
std::optional<std::string> geometry_validity_note(const std::string& where, ForceLaw law, const BearingGeometry& g);

/// The note for a full-film law whose load reversed in a run (`where`: the joint).
std::string reversing_load_note(const std::string& where, ForceLaw law);

}  // namespace lub
