// The force-law dispatcher: see lub/bearing/film_force.hpp.
#include "lub/bearing/film_force.hpp"

namespace lub {

FilmForce film_force(ForceLaw law, const BearingGeometry& g, double viscosity_Pa_s,
                     const BearingState& s, FiniteBearingSolver* solver) {
  switch (law) {
    case ForceLaw::pinkus_sternlicht:
      return film_force_pinkus_sternlicht(g, viscosity_Pa_s, s);
    case ForceLaw::frene_long:
      return film_force_frene_long(g, viscosity_Pa_s, s);
    case ForceLaw::frene_short:
      return film_force_frene_short(g, viscosity_Pa_s, s);
    case ForceLaw::gumbel_long:
      return film_force_gumbel_long(g, viscosity_Pa_s, s);
    case ForceLaw::gumbel_short:
      return film_force_gumbel_short(g, viscosity_Pa_s, s);
    case ForceLaw::pinkus_sternlicht_continuous:
      return film_force_pinkus_sternlicht_continuous(g, viscosity_Pa_s, s);
    case ForceLaw::finite_reynolds:
      if (solver) return solver->solve(g, viscosity_Pa_s, s);
      return FiniteBearingSolver().solve(g, viscosity_Pa_s, s);
  }
  return FilmForce{};  // unreachable for a valid enumerator
}

FilmForce film_force(ForceLaw law, const BearingGeometry& g, double viscosity_Pa_s,
                     const BearingState& s) {
  return film_force(law, g, viscosity_Pa_s, s, nullptr);
}

}  // namespace lub
