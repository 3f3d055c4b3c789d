// Tests of the dry-contact effect (core/src/bearing/contact.cpp) and of its wiring: scene keys
// (effects.contact, and the finite_reynolds options on a lubricated joint), the model applying
// contact only to the joints the scene names, the film law never evaluated above the hand-over
// band, and the restitution of a free impact.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lub/bearing/contact.hpp"
#include "lub/mechanism/builder.hpp"
#include "lub/mechanism/model.hpp"
#include "fixtures/bearing_fixture.hpp"
#include "fixtures/bearing_scene.hpp"

namespace {

using bearing_fixture::state;

using lub::BearingState;
using lub::ContactLaw;
using lub::FilmForce;
using nlohmann::json;

ContactLaw test_law() {
  ContactLaw c;
  c.stiffness = 2.0e10;
  c.exponent = 1.5;
  c.damping_s_per_m = 0.3;
  c.eps_start = 0.96;
  c.eps_end = 0.99;
  return c;
}

TEST(Contact, ConformalCylinderStiffness) {
  // K = 4/(3(σ_J + σ_B)) (R_J R_B/(R_B − R_J))^(1/2), σ = (1 − ν²)/E; steel on steel,
  // R_J = 9.5 mm, R_B = 10 mm: hand-computed. A few roundings: 1e-14.
  const lub::ContactMaterial steel{207e9, 0.3};
  const double sigma = (1.0 - 0.09) / 207e9;
  const double expect = 4.0 / (3.0 * 2.0 * sigma) * std::sqrt(0.0095 * 0.010 / 0.0005);
  EXPECT_NEAR(lub::conformal_cylinder_stiffness(0.0095, 0.010, steel, steel), expect, 1e-14 * expect);
}

TEST(Contact, FilmWeightIsAC2SmoothStepOverTheBand) {
  const ContactLaw c = test_law();
  EXPECT_EQ(lub::film_weight(c, 0.5), 1.0);
  EXPECT_EQ(lub::film_weight(c, c.eps_start), 1.0);
  EXPECT_EQ(lub::film_weight(c, c.eps_end), 0.0);
  EXPECT_EQ(lub::film_weight(c, 1.2), 0.0);
  EXPECT_NEAR(lub::film_weight(c, 0.5 * (c.eps_start + c.eps_end)), 0.5, 1e-15);
  // Monotone, and first and second derivatives vanish at both ends (smootherstep): central
  // differences with h = 1e-5 of the band, inside the band, are O(h) and O(h²)-small there.
  double prev = 1.0;
  for (int i = 1; i < 100; ++i) {
    const double w = lub::film_weight(c, c.eps_start + (c.eps_end - c.eps_start) * i / 100.0);
    EXPECT_LT(w, prev);
    prev = w;
  }
  const double band = c.eps_end - c.eps_start, h = 1e-5 * band;
  for (double e : {c.eps_start, c.eps_end}) {
    const double d1 = (lub::film_weight(c, e + h) - lub::film_weight(c, e - h)) / (2.0 * h);
    EXPECT_LT(std::fabs(d1) * band, 1e-8) << e;
  }
}

TEST(Contact, HuntCrossleyNormalForce) {
  const ContactLaw c = test_law();
  const double cl = 5e-4;
  EXPECT_EQ(lub::contact_normal_force_N(c, cl, 0.9, 5.0), 0.0);      // gap
  EXPECT_EQ(lub::contact_normal_force_N(c, cl, c.eps_start, 5.0), 0.0);
  const double eps = 0.98, ed = 3.0;
  const double delta = cl * (eps - c.eps_start);
  const double expect = c.stiffness * std::pow(delta, 1.5) * (1.0 + c.damping_s_per_m * cl * ed);
  EXPECT_NEAR(lub::contact_normal_force_N(c, cl, eps, ed), expect, 1e-14 * expect);
  // Separating fast: no adhesion (clamped at 0).
  EXPECT_EQ(lub::contact_normal_force_N(c, cl, eps, -1e4), 0.0);
  // Beyond ε = 1 the contact still acts (deep penetration is the contact's business).
  EXPECT_GT(lub::contact_normal_force_N(c, cl, 1.02, 0.0), 0.0);
}

TEST(Contact, ElasticEnergyIsThePotentialOfTheElasticForce) {
  // dV/dε = c · K δ^n (the elastic part of F_n): central difference, h = 1e-7, O(h²) ≈ 1e-10.
  const ContactLaw c = test_law();
  const double cl = 5e-4;
  EXPECT_EQ(lub::contact_elastic_energy_J(c, cl, 0.9), 0.0);
  for (double eps : {0.97, 0.985, 1.01}) {
    const double h = 1e-7;
    const double dv = (lub::contact_elastic_energy_J(c, cl, eps + h) - lub::contact_elastic_energy_J(c, cl, eps - h)) /
                      (2.0 * h);
    const double f = lub::contact_normal_force_N(c, cl, eps, 0.0);
    EXPECT_NEAR(dv, cl * f, 1e-6 * cl * f) << eps;
  }
}

TEST(Contact, HandOverNeverEvaluatesTheFilmAboveTheBand) {
  const ContactLaw c = test_law();
  const double cl = 5e-4;
  int calls = 0;
  double max_eps_seen = 0.0;
  const auto film = [&](const BearingState& s) {
    ++calls;
    max_eps_seen = std::max(max_eps_seen, s.eps);
    return FilmForce{-1000.0, 200.0};
  };
  // Below the band: the film alone, exactly.
  FilmForce f = lub::force_with_contact(c, cl, state(0.5, 1.0, 100.0), film);
  EXPECT_EQ(f.radial_N, -1000.0);
  EXPECT_EQ(f.tangential_N, 200.0);
  // Inside: weighted film + contact.
  double fn = -1.0;
  f = lub::force_with_contact(c, cl, state(0.975, 1.0, 100.0), film, &fn);
  const double w = lub::film_weight(c, 0.975);
  EXPECT_NEAR(f.radial_N, -1000.0 * w - fn, 1e-12 * 1000.0);
  EXPECT_NEAR(f.tangential_N, 200.0 * w, 1e-12 * 200.0);
  EXPECT_GT(fn, 0.0);
  // Above (and through the wall): contact alone, film not called.
  const int before = calls;
  for (double eps : {0.99, 0.995, 1.0, 1.05}) {
    f = lub::force_with_contact(c, cl, state(eps, 1.0, 100.0), film, &fn);
    EXPECT_EQ(f.tangential_N, 0.0);
    EXPECT_EQ(f.radial_N, -fn);
  }
  EXPECT_EQ(calls, before);
  EXPECT_LT(max_eps_seen, c.eps_end);
}

TEST(Contact, RestitutionOfAFreeImpactAtTheReferenceSpeed) {
  // A mass m driven into the wall at v_ref by nothing but the contact force (RK4, small steps):
  // the rebound speed over the impact speed is the effective restitution. Lankarani–Nikravesh
  // is derived for c_e near 1; at c_e = 0.9 its prediction is good to ~2 % (observed ~1 %).
  const double m = 0.2, v_ref = 0.5, cl = 5e-4;
  for (double ce : {0.9, 0.95}) {
    lub::ContactSpec spec;
    spec.stiffness = 5e9;
    spec.restitution = ce;
    spec.reference_impact_speed_m_s = v_ref;
    spec.handover_start_eps = 0.98;
    spec.handover_end_eps = 0.99;
    lub::BearingGeometry g;
    g.journal_radius_m = 0.0095;
    g.bearing_radius_m = 0.0100;
    g.length_m = 0.04;
    const ContactLaw c = lub::resolve_contact(spec, g);
    // State: x = c(ε − ε_a) (penetration), v = dx/dt; start touching, moving in at v_ref.
    double x = 0.0, v = v_ref;
    const double dt = 1e-8;
    const auto acc = [&](double xx, double vv) {
      return -lub::contact_normal_force_N(c, cl, c.eps_start + xx / cl, vv / cl) / m;
    };
    for (int k = 0; k < 10000000 && !(x < 0.0 && v < 0.0); ++k) {
      const double a1 = acc(x, v);
      const double a2 = acc(x + 0.5 * dt * v, v + 0.5 * dt * a1);
      const double a3 = acc(x + 0.5 * dt * (v + 0.5 * dt * a1), v + 0.5 * dt * a2);
      const double a4 = acc(x + dt * (v + 0.5 * dt * a2), v + dt * a3);
      x += dt * (v + dt * (a1 + a2 + a3) / 6.0);
      v += dt * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0;
    }
    const double e_eff = -v / v_ref;
    EXPECT_NEAR(e_eff, ce, 0.02 * ce) << "c_e=" << ce;
    std::printf("[ measured ] lankarani_nikravesh c_e=%.2f at v_ref: effective restitution %.4f\n", ce, e_eff);
  }
}

// --- Scene and model wiring ---------------------------------------------------------------

json bearing_scene(const std::string& law) { return scene_fixture::grounded_bearing(law); }

json contact_block() {
  return json{{"stiffness_N_per_m_n", 1e10}, {"restitution", 0.9}, {"handover_eps", {0.97, 0.995}}};
}

using scene_fixture::parse_error;

TEST(ContactScene, AbsentMeansNoContactCode) {
  const lub::Model m = lub::build_model(lub::parse_scene(bearing_scene("gumbel_short")));
  ASSERT_EQ(m.films.size(), 1u);
  EXPECT_FALSE(m.films[0].contact.has_value());
  // Without contact the journal through the wall is outside the model (status 1).
  lub::Workspace ws(m);
  const double q[6] = {0, 0, 0, 0.0006, 0, 0};  // e = 0.6 mm > c = 0.5 mm
  const double v[6] = {0, 0, 0, 0, 0, 0};
  double a[6];
  EXPECT_EQ(lub::evaluate(m, ws, lub::Stabilisation{}, 0.0, q, v, a), lub::EvalStatus::outside_domain);
}

TEST(ContactScene, NamedContactActsThroughTheWallWithoutTheFilm) {
  json doc = bearing_scene("gumbel_short");
  doc["effects"]["contact"] = contact_block();
  const lub::Scene scene = lub::parse_scene(doc);
  ASSERT_TRUE(scene.contact.has_value());
  const lub::Model m = lub::build_model(scene);
  ASSERT_TRUE(m.films[0].contact.has_value());
  EXPECT_EQ(m.films[0].contact->stiffness, 1e10);
  lub::Workspace ws(m);
  const double v[6] = {0, 0, 0, 0, 0, 0};
  double a[6];
  // ε = 1.2: contact alone, pushing the journal back towards the centre (−x), film not called.
  const double q[6] = {0, 0, 0, 0.0006, 0, 0};
  const long long film_before = ws.counters.film;
  ASSERT_EQ(lub::evaluate(m, ws, lub::Stabilisation{}, 0.0, q, v, a), lub::EvalStatus::ok);
  EXPECT_EQ(ws.counters.film, film_before);
  EXPECT_LT(ws.films[0].F.x(), 0.0);
  EXPECT_NEAR(ws.films[0].F.x(), -ws.contact_N[0], 1e-9 * ws.contact_N[0]);
  // ε = 0.5: the film alone, same force as without the effect.
  const double q2[6] = {0, 0, 0, 0.00025, 0, 0};
  const double v2[6] = {0, 0, 0, 0.001, 0.002, 50.0};
  ASSERT_EQ(lub::evaluate(m, ws, lub::Stabilisation{}, 0.0, q2, v2, a), lub::EvalStatus::ok);
  const lub::Model m0 = lub::build_model(lub::parse_scene(bearing_scene("gumbel_short")));
  lub::Workspace ws0(m0);
  ASSERT_EQ(lub::evaluate(m0, ws0, lub::Stabilisation{}, 0.0, q2, v2, a), lub::EvalStatus::ok);
  EXPECT_EQ(ws.films[0].F.x(), ws0.films[0].F.x());
  EXPECT_EQ(ws.films[0].F.y(), ws0.films[0].F.y());
  EXPECT_EQ(ws.contact_N[0], 0.0);
}

TEST(ContactScene, MaterialsGiveTheConformalStiffness) {
  json doc = bearing_scene("frene_long");
  json c = contact_block();
  c.erase("stiffness_N_per_m_n");
  c["materials"] = {{"journal", {{"youngs_modulus_Pa", 207e9}, {"poisson_ratio", 0.3}}},
                    {"bearing", {{"youngs_modulus_Pa", 110e9}, {"poisson_ratio", 0.34}}}};
  c["model"] = "hunt_crossley";
  c["reference_impact_speed_m_s"] = 0.5;
  doc["effects"]["contact"] = c;
  const lub::Model m = lub::build_model(lub::parse_scene(doc));
  const double K = lub::conformal_cylinder_stiffness(0.0095, 0.010, {207e9, 0.3}, {110e9, 0.34});
  EXPECT_NEAR(m.films[0].contact->stiffness, K, 1e-14 * K);
  EXPECT_NEAR(m.films[0].contact->damping_s_per_m, 3.0 * (1.0 - 0.9) / (2.0 * 0.5), 1e-15);
}

TEST(ContactScene, BadInputNamesTheFieldAndRule) {
  const auto with = [](const json& c) {
    json doc = bearing_scene("gumbel_long");
    doc["effects"]["contact"] = c;
    return parse_error(doc);
  };
  json c = contact_block();
  c["handover_eps"] = {0.99, 0.97};
  EXPECT_NE(with(c).find("effects.contact.handover_eps"), std::string::npos) << with(c);
  EXPECT_NE(with(c).find("0 < eps_start < eps_end < 1"), std::string::npos);
  c = contact_block();
  c["handover_eps"] = {0.97, 1.0};
  EXPECT_NE(with(c).find("eps_end < 1"), std::string::npos);
  c = contact_block();
  c["restitution"] = 1.5;
  EXPECT_NE(with(c).find("effects.contact.restitution"), std::string::npos) << with(c);
  c = contact_block();
  c.erase("stiffness_N_per_m_n");
  EXPECT_NE(with(c).find("exactly one of"), std::string::npos) << with(c);
  c = contact_block();
  c["joints"] = {"fix"};
  EXPECT_NE(with(c).find("effects.contact.joints[0]"), std::string::npos) << with(c);
  c = contact_block();
  c["stiffnes"] = 1.0;  // typo: unknown keys are errors
  EXPECT_NE(with(c).find("stiffnes"), std::string::npos) << with(c);
  c = contact_block();
  c["model"] = "hertz";
  EXPECT_NE(with(c).find("effects.contact.model"), std::string::npos) << with(c);
}

TEST(ContactScene, OnlyTheNamedJointsGetContact) {
  json doc = bearing_scene("gumbel_long");
  json second = doc["joints"][1];
  second["name"] = "bearing2";
  doc["bodies"].push_back({{"name", "shaft2"}, {"mass_kg", 0.5}, {"inertia_kg_m2", 0.002}});
  second["journal_body"] = "shaft2";
  doc["joints"].push_back(second);
  json c = contact_block();
  c["joints"] = {"bearing2"};
  doc["effects"]["contact"] = c;
  const lub::Model m = lub::build_model(lub::parse_scene(doc));
  ASSERT_EQ(m.films.size(), 2u);
  EXPECT_FALSE(m.films[0].contact.has_value());
  EXPECT_TRUE(m.films[1].contact.has_value());
}

TEST(FiniteBearingScene, OptionsAreParsedAndValidated) {
  json doc = bearing_scene("finite_reynolds");
  doc["joints"][1]["cavitation"] = "gumbel";
  doc["joints"][1]["reynolds_n_theta"] = 40;
  doc["joints"][1]["reynolds_n_z"] = 5;
  doc["joints"][1]["reynolds_groove_at_max_film"] = true;
  const lub::Scene scene = lub::parse_scene(doc);
  EXPECT_EQ(scene.joints[1].finite.cavitation, lub::Cavitation::gumbel);
  EXPECT_EQ(scene.joints[1].finite.n_theta, 40);
  EXPECT_EQ(scene.joints[1].finite.n_z, 5);
  EXPECT_TRUE(scene.joints[1].finite.groove_at_max_film);
  // The model owns a solver per finite film, in the workspace; it evaluates.
  const lub::Model m = lub::build_model(scene);
  lub::Workspace ws(m);
  ASSERT_TRUE(ws.film_solvers[0].has_value());
  EXPECT_EQ(ws.film_solvers[0]->options().n_theta, 40);
  const double q[6] = {0, 0, 0, 0.0002, 0.0001, 0};
  const double v[6] = {0, 0, 0, 0.001, 0.0, 100.0};
  double a[6];
  ASSERT_EQ(lub::evaluate(m, ws, lub::Stabilisation{}, 0.0, q, v, a), lub::EvalStatus::ok);
  EXPECT_TRUE(std::isfinite(ws.films[0].F.x()) && ws.films[0].F.norm() > 0.0);
  // Errors name the path, value and rule.
  doc["joints"][1]["cavitation"] = "elrod";
  std::string err = parse_error(doc);
  EXPECT_NE(err.find("joints[1].cavitation"), std::string::npos) << err;
  EXPECT_NE(err.find("gumbel, reynolds, sommerfeld"), std::string::npos) << err;
  doc["joints"][1]["cavitation"] = "reynolds";
  doc["joints"][1]["reynolds_n_theta"] = 4;
  err = parse_error(doc);
  EXPECT_NE(err.find("joints[1].reynolds_n_theta"), std::string::npos) << err;
  // Closed-form laws accept the keys (a sweep may vary force_law with them in the scene).
  doc["joints"][1]["reynolds_n_theta"] = 32;
  doc["joints"][1]["force_law"] = "gumbel_long";
  EXPECT_EQ(parse_error(doc), "");
  // Every law name parses in a scene (so sweeps can set it by JSON Pointer).
  for (const char* law : {"gumbel_long", "gumbel_short", "pinkus_sternlicht_continuous", "finite_reynolds"}) {
    json d = bearing_scene(law);
    EXPECT_EQ(parse_error(d), "") << law;
    lub::apply_override(d, std::string("/joints/1/force_law=") + law);
    EXPECT_EQ(lub::parse_scene(d).joints[1].law == lub::ForceLaw::pinkus_sternlicht, false) << law;
  }
}

}  // namespace
