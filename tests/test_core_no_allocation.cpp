// The right-hand side allocates nothing: after a warm-up, MultibodySystem::rhs (both
// formulations), roots and quadrature_rhs, and lub::evaluate, make no heap allocation, for
// the reference slider-crank with each force law (and a sliding film of the printed law).
// This executable replaces the global allocation functions with counting ones: operator
// new, and with glibc malloc/calloc/realloc themselves, which Eigen uses directly.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "lub/io/json_reader.hpp"
#include "lub/mechanism/builder.hpp"
#include "lub/mechanism/model.hpp"
#include "lub/scene/scene.hpp"
#include "lub/formulation/multibody_system.hpp"

namespace {
std::atomic<long long> g_allocations{0};
}  // namespace

#if defined(__GLIBC__)
// glibc lets a program interpose malloc; forward to its own implementation.
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);
void* malloc(std::size_t n) {
  ++g_allocations;
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t s) {
  ++g_allocations;
  return __libc_calloc(n, s);
}
void* realloc(void* p, std::size_t n) {
  ++g_allocations;
  return __libc_realloc(p, n);
}
void free(void* p) { __libc_free(p); }
}
#endif

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

using lub::Formulation;

struct Fixture {
  lub::Scene scene;
  lub::Model model;
  std::vector<double> qv;  // consistent (q, v) at t = 0
  explicit Fixture(const std::string& law) {
    nlohmann::json doc = lub::read_json_file(std::string(LUB_SOURCE_DIR) + "/configs/scenes/slider_crank.json");
    doc["joints"][3]["force_law"] = law;
    scene = lub::parse_scene(doc);
    model = lub::build_model(scene);
    Eigen::VectorXd q, v;
    lub::assemble_initial_state(model, scene, 0.0, q, v);
    qv.assign(q.data(), q.data() + model.nq);
    qv.insert(qv.end(), v.data(), v.data() + model.nq);
  }
};

// Allocations made by f() (after the caller's warm-up).
template <class F>
long long allocations(F&& f) {
  const long long before = g_allocations.load();
  f();
  return g_allocations.load() - before;
}

// The integrator's state near y0, different at every call k (no cache can answer it):
// the journal moved off-centre in its clearance and a small velocity perturbation.
std::vector<double> state_near(const std::vector<double>& y0, int k) {
  std::vector<double> y = y0;
  const size_t n = y.size() / 2;
  for (size_t i = 0; i < n; ++i) {
    y[i] += 1e-6 * (1.0 + 0.1 * k) * (i % 2 ? 1.0 : -1.0);
    y[n + i] += 1e-3 * (1.0 + 0.1 * k) * (i % 3 ? 1.0 : -0.5);
  }
  return y;
}

void expect_no_allocation(const std::string& law, Formulation form, bool sliding) {
  Fixture fx(law);
  const lub::Model& m = fx.model;
  lub::Workspace ws(m);
  const lub::Stabilisation stab = lub::stabilisation(fx.scene);
  lub::MultibodySystem sys(m, ws, stab, 0.99, /*energy=*/true, form);
  sys.partition(0.0, fx.qv.data());
  std::vector<double> y0(static_cast<size_t>(sys.size())), ydot(y0.size());
  sys.reduce(fx.qv.data(), y0.data());
  std::vector<double> g(static_cast<size_t>(sys.num_roots())), qdot(2), qdd(static_cast<size_t>(m.nq));
  if (sliding) {
    ASSERT_EQ(m.n_switching, 1) << law;
    ws.film_mode[0] = lub::FilmMode::sliding;
    ws.slide_radius[0] = 0.2 * m.films[0].clearance;
  }
  auto calls = [&](int k) {
    const double t = 1e-9 * k;  // the driver turns the crank: keep the journal inside
    const std::vector<double> y = state_near(y0, k);  // allocated outside the counted calls
    const std::vector<double> yb = state_near(fx.qv, k);
    return [&m, &ws, &stab, &sys, &ydot, &g, &qdot, &qdd, t, y, yb] {
      EXPECT_EQ(sys.rhs(t, y.data(), ydot.data()), 0);
      EXPECT_EQ(sys.roots(t, y.data(), g.data()), 0);
      EXPECT_EQ(sys.quadrature_rhs(t, y.data(), qdot.data()), 0);
      EXPECT_EQ(lub::evaluate(m, ws, stab, t, yb.data(), yb.data() + m.nq, qdd.data()), lub::EvalStatus::ok);
    };
  };
  for (int k = 0; k < 3; ++k) calls(k)();  // warm-up
  for (int k = 3; k < 8; ++k) {
    auto f = calls(k);
    EXPECT_EQ(allocations(f), 0) << law << " " << lub::name_of(form)
                                 << (sliding ? " sliding" : "") << ", call " << k;
  }
}

class NoAllocation : public testing::TestWithParam<std::string> {};

TEST_P(NoAllocation, Baumgarte) { expect_no_allocation(GetParam(), Formulation::baumgarte, false); }
TEST_P(NoAllocation, Partitioned) { expect_no_allocation(GetParam(), Formulation::partitioned, false); }
TEST_P(NoAllocation, Joint) {
  // The ideal slider-crank closes a loop of ideal joints: no tree, it runs partitioned.
  if (GetParam() == "ideal") GTEST_SKIP() << "no joint-coordinate tree for a loop of ideal joints";
  expect_no_allocation(GetParam(), Formulation::joint, false);
}

INSTANTIATE_TEST_SUITE_P(Laws, NoAllocation,
                         testing::Values("pinkus_sternlicht", "frene_long", "frene_short", "gumbel_long",
                                         "gumbel_short", "pinkus_sternlicht_continuous", "finite_reynolds",
                                         "ideal"));

TEST(NoAllocationSliding, PrintedLawHeldOnEpsDotZero) {
  expect_no_allocation("pinkus_sternlicht", Formulation::baumgarte, true);
  expect_no_allocation("pinkus_sternlicht", Formulation::partitioned, true);
  expect_no_allocation("pinkus_sternlicht", Formulation::joint, true);
}

TEST(NoAllocationCounter, SeesAHeapAllocation) {
  // The counter works: a vector and an Eigen temporary are both seen.
  EXPECT_GE(allocations([] { std::vector<double> v(100, 1.0); }), 1);
  EXPECT_GE(allocations([] {
    Eigen::VectorXd a = Eigen::VectorXd::Ones(50);
    volatile double s = (a + a).eval().sum();
    (void)s;
  }),
            1);
}

}  // namespace
