// Dry contact with a smooth hand-over from the film: see lub/bearing/contact.hpp.
#include "lub/bearing/contact.hpp"

#include <cmath>

namespace lub {

double conformal_cylinder_stiffness(double journal_radius_m, double bearing_radius_m,
                                    const ContactMaterial& journal, const ContactMaterial& bearing) {
  const double sj = (1.0 - journal.poisson_ratio * journal.poisson_ratio) / journal.youngs_modulus_Pa;
  const double sb = (1.0 - bearing.poisson_ratio * bearing.poisson_ratio) / bearing.youngs_modulus_Pa;
  const double r_eff = journal_radius_m * bearing_radius_m / (bearing_radius_m - journal_radius_m);
  return 4.0 / (3.0 * (sj + sb)) * std::sqrt(r_eff);
}

ContactLaw resolve_contact(const ContactSpec& spec, const BearingGeometry& g) {
  ContactLaw law;
  law.stiffness = spec.stiffness ? *spec.stiffness
                                 : conformal_cylinder_stiffness(g.journal_radius_m, g.bearing_radius_m,
                                                                *spec.journal_material,
                                                                *spec.bearing_material);
  law.exponent = spec.exponent;
  const double ce = spec.restitution;
  law.damping_s_per_m = spec.model == ContactModel::lankarani_nikravesh
                            ? 3.0 * (1.0 - ce * ce) / (4.0 * spec.reference_impact_speed_m_s)
                            : 3.0 * (1.0 - ce) / (2.0 * spec.reference_impact_speed_m_s);
  law.eps_start = spec.handover_start_eps;
  law.eps_end = spec.handover_end_eps;
  return law;
}

double film_weight(const ContactLaw& law, double eps) {
  if (eps <= law.eps_start) return 1.0;
  if (eps >= law.eps_end) return 0.0;
  const double x = (eps - law.eps_start) / (law.eps_end - law.eps_start);
  return 1.0 - x * x * x * (x * (6.0 * x - 15.0) + 10.0);
}

double contact_normal_force_N(const ContactLaw& law, double clearance_m, double eps, double eps_dot) {
  if (!(eps > law.eps_start)) return 0.0;
  const double delta = clearance_m * (eps - law.eps_start);
  const double elastic = law.stiffness * std::pow(delta, law.exponent);
  const double f = elastic * (1.0 + law.damping_s_per_m * clearance_m * eps_dot);
  return f > 0.0 ? f : 0.0;
}

double contact_elastic_energy_J(const ContactLaw& law, double clearance_m, double eps) {
  if (!(eps > law.eps_start)) return 0.0;
  const double delta = clearance_m * (eps - law.eps_start);
  return law.stiffness * std::pow(delta, law.exponent + 1.0) / (law.exponent + 1.0);
}

}  // namespace lub
