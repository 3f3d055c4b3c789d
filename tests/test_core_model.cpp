// The lubricated joint inside the model: bearing kinematics (ε, ε̇, γ̇, wedge speed) and
// the film force's frame invariance, scene parsing and --set overrides.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "lub/bearing/film_force.hpp"
#include "lub/common/check.hpp"
#include "lub/io/json_reader.hpp"
#include "lub/mechanism/builder.hpp"
#include "lub/mechanism/model.hpp"
#include "fixtures/bearing_scene.hpp"

namespace {

using Eigen::Vector2d;
using nlohmann::json;

// Two free bodies joined only by a lubricated joint; offsets of the bearing and journal
// centres from the centres of mass are parameters.
json two_body_scene(const std::string& law, Vector2d s_bearing, Vector2d s_journal) {
  json joint = scene_fixture::paper_joint(law);
  joint["bearing_point_m"] = {s_bearing.x(), s_bearing.y()};
  joint["journal_point_m"] = {s_journal.x(), s_journal.y()};
  return scene_fixture::housing_and_shaft(json::array({joint}));
}

struct BodyPose {
  Vector2d r, rd;
  double phi, phid;
};

// Film force on the journal for the given body states.
Vector2d film_force(const lub::Model& m, const BodyPose& housing, const BodyPose& shaft) {
  lub::Workspace ws(m);
  const double q[6] = {housing.r.x(), housing.r.y(), housing.phi, shaft.r.x(), shaft.r.y(), shaft.phi};
  const double v[6] = {housing.rd.x(), housing.rd.y(), housing.phid, shaft.rd.x(), shaft.rd.y(), shaft.phid};
  double a[6];
  EXPECT_EQ(lub::evaluate(m, ws, lub::Stabilisation{}, 0.0, q, v, a), lub::EvalStatus::ok);
  return ws.films[0].F;
}

Vector2d rot(double a, const Vector2d& v) {
  return {std::cos(a) * v.x() - std::sin(a) * v.y(), std::sin(a) * v.x() + std::cos(a) * v.y()};
}
Vector2d perp(const Vector2d& v) { return {-v.y(), v.x()}; }

// Places the shaft so that its journal centre sits at bearing centre + e, moving at
// bearing-centre velocity + ė.
BodyPose shaft_for(const BodyPose& h, Vector2d sb, Vector2d sj, double phi_s, double phid_s, Vector2d e,
                   Vector2d edot) {
  const Vector2d Pb = h.r + rot(h.phi, sb);
  const Vector2d Vb = h.rd + h.phid * perp(rot(h.phi, sb));
  BodyPose s;
  s.phi = phi_s;
  s.phid = phid_s;
  s.r = Pb + e - rot(phi_s, sj);
  s.rd = Vb + edot - phid_s * perp(rot(phi_s, sj));
  return s;
}

TEST(FilmElement, JournalOrBearingRotatingGiveTheSameForce) {
  // The wedge term depends on the sum of the surface speeds seen from the line of
  // centres, ω_J + ω_B − 2γ̇: a journal spinning at ω in a still bearing and a bearing
  // spinning at ω round a still journal (same e, ė) carry the same film. (The paper's
  // ω = φ̇_j − φ̇_i with a global γ̇ would flip the sign of the wedge term here.)
  for (const std::string law : {"pinkus_sternlicht", "frene_long", "frene_short"}) {
    const lub::Model m = lub::build_model(lub::parse_scene(two_body_scene(law, {0, 0}, {0, 0})));
    const Vector2d e(2.0e-4, 1.5e-4), edot(0.01, -0.02);
    const double omega = 300.0;
    BodyPose h{{0.1, 0.2}, {0, 0}, 0.0, 0.0};
    const Vector2d Fa = film_force(m, h, shaft_for(h, {0, 0}, {0, 0}, 0.0, omega, e, edot));
    h.phid = omega;
    const Vector2d Fb = film_force(m, h, shaft_for(h, {0, 0}, {0, 0}, 0.0, 0.0, e, edot));
    EXPECT_GT(Fa.norm(), 1.0) << law;
    if (!(Fa.norm() > 1.0)) continue;
    // Same formula, evaluated from different body states: a few ulps of the force.
    EXPECT_LT((Fa - Fb).norm(), 1e-12 * Fa.norm()) << law;
  }
}

TEST(FilmElement, ForceIsObjectiveUnderARotatingObserver) {
  // Describe the same motion from a frame rotated by α and spinning at Ω: positions
  // rotate, every angle gains α, every angular velocity gains Ω, and velocities gain the
  // frame's rigid motion. The film force must simply rotate by α. Offsets of the
  // bearing and journal centres from the centres of mass exercise the φ̇ × s terms.
  const Vector2d sb(0.03, -0.01), sj(-0.05, 0.02);
  for (const std::string law : {"pinkus_sternlicht", "frene_long", "frene_short"}) {
    const lub::Model m = lub::build_model(lub::parse_scene(two_body_scene(law, sb, sj)));
    const BodyPose h{{0.1, 0.2}, {0.3, -0.1}, 0.4, 12.0};
    const BodyPose s = shaft_for(h, sb, sj, -0.7, 250.0, {-3.0e-4, 2.0e-4}, {0.05, 0.02});
    const Vector2d F = film_force(m, h, s);
    for (const double alpha : {0.3, 2.0, -1.1}) {
      for (const double Omega : {0.0, 40.0, -500.0}) {
        auto transform = [&](const BodyPose& b) {
          BodyPose o;
          o.r = rot(alpha, b.r);
          o.rd = rot(alpha, b.rd) + Omega * perp(o.r);
          o.phi = b.phi + alpha;
          o.phid = b.phid + Omega;
          return o;
        };
        const Vector2d F2 = film_force(m, transform(h), transform(s));
        EXPECT_LT((F2 - rot(alpha, F)).norm(), 1e-10 * F.norm())
            << law << " alpha=" << alpha << " Omega=" << Omega;
      }
    }
  }
}

TEST(FilmElement, CentredJournalHasFiniteForceAlongItsVelocity) {
  // ε = 0 exactly: the line of centres is taken along ė, and the Sommerfeld laws give
  // the isotropic squeeze damping F = −(K/c) ė with K = 12πμLR³/c² (long bearing).
  const lub::Model m = lub::build_model(lub::parse_scene(two_body_scene("frene_long", {0, 0}, {0, 0})));
  const BodyPose h{{0, 0}, {0, 0}, 0, 0};
  const Vector2d edot(0.03, -0.04);
  const Vector2d F = film_force(m, h, shaft_for(h, {0, 0}, {0, 0}, 0, 100.0, {0, 0}, edot));
  const double c = 0.5e-3, K = 12 * M_PI * 0.4 * 0.04 * std::pow(0.0095, 3) / (c * c);
  EXPECT_LT((F + K / c * edot).norm(), 1e-12 * F.norm());
  // And no force at rest in the centre.
  const Vector2d F0 = film_force(m, h, shaft_for(h, {0, 0}, {0, 0}, 0, 100.0, {0, 0}, {0, 0}));
  EXPECT_EQ(F0.norm(), 0.0);
}

TEST(SceneOverrides, SetByJsonPointer) {
  json doc = two_body_scene("frene_long", {0, 0}, {0, 0});
  lub::apply_override(doc, "/joints/0/viscosity_Pa_s=0.04");
  lub::apply_override(doc, "/joints/0/force_law=frene_short");  // bare word: a string
  lub::apply_override(doc, "/solver={\"rtol\": 1e-8}");          // new key of an object
  const lub::Scene s = lub::parse_scene(doc);
  EXPECT_DOUBLE_EQ(s.joints[0].viscosity_Pa_s, 0.04);
  EXPECT_EQ(s.joints[0].law, lub::ForceLaw::frene_short);
  EXPECT_DOUBLE_EQ(s.solver.rtol, 1e-8);
  EXPECT_THROW(lub::apply_override(doc, "/nothing/here=1"), lub::InputError);
  EXPECT_THROW(lub::apply_override(doc, "no_equals_sign"), lub::InputError);
}

TEST(SceneValidation, ErrorsNameThePathTheValueAndTheRule) {
  json doc = two_body_scene("frene_long", {0, 0}, {0, 0});
  doc["joints"][0]["journal_radius_m"] = 0.011;
  try {
    lub::parse_scene(doc);
    FAIL() << "accepted a journal larger than its bearing";
  } catch (const lub::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("joints[0].journal_radius_m = 0.011"), std::string::npos) << msg;
    EXPECT_NE(msg.find("must be < bearing_radius_m"), std::string::npos) << msg;
  }
  doc = two_body_scene("frene_long", {0, 0}, {0, 0});
  doc["joints"][0]["viscosty_Pa_s"] = 0.4;  // typo
  EXPECT_THROW(lub::parse_scene(doc), lub::InputError);
}

}  // namespace

// A workspace is built for one model: handing it another is a bug (an internal invariant,
// lub::InternalError, always checked), not bad input (lub::InputError).
TEST(ModelWorkspace, AWorkspaceOfAnotherModelIsAnInternalError) {
  json doc = two_body_scene("frene_long", {0, 0}, {0, 0});
  const lub::Model m = lub::build_model(lub::parse_scene(doc));
  doc["bodies"].push_back({{"name", "extra"}, {"mass_kg", 1.0}, {"inertia_kg_m2", 0.01}});
  const lub::Model other = lub::build_model(lub::parse_scene(doc));
  lub::Workspace ws(other);
  std::vector<double> q(static_cast<size_t>(m.nq), 0.0), v(q), a(q);
  q[3] = 1e-5;  // journal off centre
  EXPECT_THROW(lub::evaluate(m, ws, lub::Stabilisation{}, 0.0, q.data(), v.data(), a.data()), lub::InternalError);
  try {
    lub::evaluate(m, ws, lub::Stabilisation{}, 0.0, q.data(), v.data(), a.data());
  } catch (const lub::InputError&) {
    ADD_FAILURE() << "a broken invariant must not read as bad input";
  } catch (const lub::InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("workspace built for a model"), std::string::npos) << e.what();
  }
  lub::Workspace own(m);
  EXPECT_EQ(lub::evaluate(m, own, lub::Stabilisation{}, 0.0, q.data(), v.data(), a.data()), lub::EvalStatus::ok);
}

// body_trig keeps a body's sin/cos while its angle is unchanged (Workspace::trig_phi): an
// evaluation must give bit for bit what a fresh workspace gives, whichever angles changed
// since the last one — none, one body's, all, and back to an earlier angle.
TEST(ModelWorkspace, KeptTrigonometryChangesNoResult) {
  json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
  const lub::Scene s = lub::parse_scene(doc);
  const lub::Model m = lub::build_model(s);
  Eigen::VectorXd q0, v0;
  lub::assemble_initial_state(m, s, 0.0, q0, v0);
  lub::Workspace kept(m);
  std::vector<double> a(static_cast<size_t>(m.nq)), b(a);
  auto q = q0;
  auto check = [&](const char* what) {
    lub::Workspace fresh(m);
    ASSERT_EQ(lub::evaluate(m, kept, lub::Stabilisation{}, 0.0, q.data(), v0.data(), a.data()), lub::EvalStatus::ok) << what;
    ASSERT_EQ(lub::evaluate(m, fresh, lub::Stabilisation{}, 0.0, q.data(), v0.data(), b.data()), lub::EvalStatus::ok) << what;
    for (int i = 0; i < m.nq; ++i) EXPECT_EQ(a[i], b[i]) << what << ", coordinate " << i;
    EXPECT_EQ(kept.cos_phi, fresh.cos_phi) << what;
    EXPECT_EQ(kept.sin_phi, fresh.sin_phi) << what;
  };
  check("first evaluation");
  q[0] += 1e-6;  // a position only
  check("no angle changed");
  q[5] += 1e-3;  // the rod's angle (body 1)
  check("one angle changed");
  for (int b = 0; b < m.nb; ++b) q[3 * b + 2] += 1e-4 * (b + 1);  // journal stays in its bearing
  check("every angle changed");
  q = q0;
  check("back to the first state");
}
