// The spanning tree of the ideal joints and its forward kinematics: see
// lub/formulation/joint_tree.hpp.
#include "lub/formulation/joint_tree.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <iterator>
#include <sstream>

#include "lub/mechanism/planar.hpp"
#include "mechanism/constraints.hpp"

namespace lub {

using Eigen::Vector2d;

namespace {

// The edge that places `child` on `parent` through ideal constraint c (revolute,
// translational or ground), in the parent's frame (see the header's equations).
TreeEdge edge_of(const Constraint& c, int parent, int child) {
  TreeEdge e;
  e.parent = parent;
  e.child = child;
  const bool forward = parent == c.body_i;  // the parent is the constraint's body i
  switch (c.kind) {
    case Constraint::Kind::revolute:
      // Φ = r_i + A_i s_i + offset − r_j − A_j s_j = 0
      e.kind = TreeEdge::Kind::revolute;
      e.s_p = forward ? c.s_i : c.s_j;
      e.s_c = forward ? c.s_j : c.s_i;
      e.o = forward ? c.offset : Vector2d(-c.offset);
      break;
    case Constraint::Kind::translational: {
      // φ_j − φ_i = φ0 and P_j − P_i = d A_i â, â the unit axis in body i's frame.
      e.kind = TreeEdge::Kind::slide;
      const Vector2d a = -perp(c.n_i) / c.n_i.norm();
      e.s_p = forward ? c.s_i : c.s_j;
      e.s_c = forward ? c.s_j : c.s_i;
      e.dphi = forward ? c.phi0 : -c.phi0;
      // From body j's frame, A_i â = A_j R(−φ0) â; the coordinate is then −d.
      e.u_p = forward ? a : rot(-c.phi0, a);
      break;
    }
    case Constraint::Kind::ground:
      e.kind = TreeEdge::Kind::fixed;
      e.s_p = c.q0.head<2>();
      e.dphi = c.q0(2);
      break;
    case Constraint::Kind::driver: break;
  }
  return e;
}

bool fail(std::string* why, const std::string& text) {
  if (why) *why = text;
  return false;
}

// Breadth first from the ground over the ideal joints; false (with the reason) on a loop.
// A body not reached hangs on the ground by a free joint, and the search goes on from it.
bool grow_tree(const Model& m, JointTree& tree, std::string* why) {
  std::vector<char> placed(static_cast<size_t>(m.nb), 0), used(m.constraints.size(), 0);
  std::deque<int> queue{kGround};
  for (int next = 0; next <= m.nb;) {
    if (queue.empty()) {
      while (next < m.nb && placed[static_cast<size_t>(next)]) ++next;
      if (next == m.nb) break;
      TreeEdge e;
      e.kind = TreeEdge::Kind::free;
      e.child = next;
      placed[static_cast<size_t>(next)] = 1;
      tree.edges.push_back(e);
      queue.push_back(next);
    }
    const int b = queue.front();
    queue.pop_front();
    for (size_t k = 0; k < m.constraints.size(); ++k) {
      const Constraint& c = m.constraints[k];
      if (used[k] || c.kind == Constraint::Kind::driver) continue;
      if (c.body_i != b && c.body_j != b) continue;
      const int other = c.body_i == b ? c.body_j : c.body_i;
      if (other == kGround || placed[static_cast<size_t>(other)]) {
        std::ostringstream msg;
        msg << "scene joint " << c.joint << " closes a loop of ideal joints";
        return fail(why, msg.str());
      }
      used[k] = 1;
      placed[static_cast<size_t>(other)] = 1;
      tree.edges.push_back(edge_of(c, b, other));
      queue.push_back(other);
    }
  }
  return true;
}

}  // namespace

std::optional<JointTree> build_joint_tree(const Model& m, std::string* why) {
  JointTree tree;
  if (!grow_tree(m, tree, why)) return std::nullopt;
  for (size_t k = 0; k < m.constraints.size(); ++k) {
    const Constraint& c = m.constraints[k];
    if (c.kind != Constraint::Kind::driver) continue;
    bool done = false;
    for (TreeEdge& e : tree.edges)
      if (e.child == c.body_j && e.kind == TreeEdge::Kind::revolute && e.driver < 0) {
        e.driver = static_cast<int>(k);
        done = true;
      }
    if (!done) {
      std::ostringstream msg;
      msg << "driver " << c.joint << " acts on body " << c.body_j << ", which no revolute joint of the tree places";
      fail(why, msg.str());
      return std::nullopt;
    }
  }
  for (TreeEdge& e : tree.edges) {
    if (e.kind == TreeEdge::Kind::fixed || e.driver >= 0) continue;
    e.dof = tree.ndof;
    tree.ndof += e.kind == TreeEdge::Kind::free ? 3 : 1;
  }
  // J's structure: a body moves with its own coordinates and its parent's.
  std::vector<std::vector<int>> moves(static_cast<size_t>(m.nb));
  for (const TreeEdge& e : tree.edges) {
    std::vector<int> d = e.parent == kGround ? std::vector<int>{} : moves[static_cast<size_t>(e.parent)];
    if (e.dof >= 0)
      for (int i = 0; i < (e.kind == TreeEdge::Kind::free ? 3 : 1); ++i) d.push_back(e.dof + i);
    std::sort(d.begin(), d.end());
    moves[static_cast<size_t>(e.child)] = d;
    tree.edge_dofs.push_back(d);
  }
  tree.dof_rows.assign(static_cast<size_t>(tree.ndof), {});
  for (int b = 0; b < m.nb; ++b)
    for (int j : moves[static_cast<size_t>(b)])
      for (int r = 0; r < 3; ++r) tree.dof_rows[static_cast<size_t>(j)].push_back(3 * b + r);
  for (int a = 0; a < tree.ndof; ++a)
    for (int b = 0; b < tree.ndof; ++b) {
      const auto &ra = tree.dof_rows[static_cast<size_t>(a)], &rb = tree.dof_rows[static_cast<size_t>(b)];
      std::vector<int> both;
      std::set_intersection(ra.begin(), ra.end(), rb.begin(), rb.end(), std::back_inserter(both));
      tree.pair_rows.push_back(both);
    }
  return tree;
}

JointKinematics::JointKinematics(const Model& m, const JointTree& tree)
    : q(Eigen::VectorXd::Zero(m.nq)), v(Eigen::VectorXd::Zero(m.nq)), c(Eigen::VectorXd::Zero(m.nq)),
      J(Eigen::MatrixXd::Zero(m.nq, tree.ndof)), cphi(static_cast<size_t>(m.nb), 1.0),
      sphi(static_cast<size_t>(m.nb), 0.0), trig_phi(static_cast<size_t>(m.nb), std::nan("")),
      at_y(2 * static_cast<size_t>(tree.ndof), 0.0) {}

bool JointKinematics::holds(double t, const double* theta, const double* theta_dot, bool derivatives) const {
  const std::ptrdiff_t nd = static_cast<std::ptrdiff_t>(at_y.size() / 2);
  return t == at_t && (at_derivatives || !derivatives) && std::equal(theta, theta + nd, at_y.begin()) &&
         std::equal(theta_dot, theta_dot + nd, at_y.begin() + nd);
}

namespace {

// The joint's coordinate, rate and (at θ̈ = 0) acceleration at t, and the angle whose
// cosine and sine a revolute's child takes: a driven joint's phase (whole turns off,
// constraints.cpp), else the coordinate.
void edge_motion(const Model& m, const TreeEdge& e, double t, const double* theta, const double* theta_dot,
                 double& x, double& xd, double& xdd, double& trig) {
  x = xd = xdd = 0.0;
  if (e.driver >= 0) {
    detail::driver_motion(m.constraints[static_cast<size_t>(e.driver)], t, x, xd, xdd, &trig);
    return;
  }
  if (e.dof >= 0) {
    x = theta[e.dof];
    xd = theta_dot[e.dof];
  }
  trig = x;
}

// A free body: its coordinates are its joint coordinates (J the identity on them, c = 0).
void free_body(const TreeEdge& e, const double* theta, const double* theta_dot, JointKinematics& k,
               bool derivatives) {
  const int cc = 3 * e.child;
  for (int i = 0; i < 3; ++i) {
    k.q(cc + i) = theta[e.dof + i];
    k.v(cc + i) = theta_dot[e.dof + i];
  }
  const size_t ch = static_cast<size_t>(e.child);
  if (k.trig_phi[ch] != k.q(cc + 2)) {
    k.cphi[ch] = std::cos(k.q(cc + 2));
    k.sphi[ch] = std::sin(k.q(cc + 2));
    k.trig_phi[ch] = k.q(cc + 2);
  }
  if (!derivatives) return;
  k.c.segment<3>(cc).setZero();
  k.J.middleRows<3>(cc).setZero();
  for (int i = 0; i < 3; ++i) k.J(cc + i, e.dof + i) = 1.0;
}

}  // namespace

void forward_kinematics(const Model& m, const JointTree& tree, double t, const double* theta,
                        const double* theta_dot, JointKinematics& k, bool derivatives) {
  const int nd = tree.ndof;
  if (k.holds(t, theta, theta_dot, derivatives)) return;
  k.at_t = t;
  std::copy(theta, theta + nd, k.at_y.begin());
  std::copy(theta_dot, theta_dot + nd, k.at_y.begin() + nd);
  k.at_derivatives = derivatives;
  double* q = k.q.data();
  double* v = k.v.data();
  double* a = k.c.data();
  for (size_t ei = 0; ei < tree.edges.size(); ++ei) {
    const TreeEdge& e = tree.edges[ei];
    const int pc = 3 * e.parent, cc = 3 * e.child;
    if (e.kind == TreeEdge::Kind::free) {
      free_body(e, theta, theta_dot, k, derivatives);
      continue;
    }
    const bool ground = e.parent == kGround;
    const double phi_p = ground ? 0.0 : q[pc + 2], w_p = ground ? 0.0 : v[pc + 2];
    const double cp = ground ? 1.0 : k.cphi[static_cast<size_t>(e.parent)];
    const double sp = ground ? 0.0 : k.sphi[static_cast<size_t>(e.parent)];
    const Vector2d r_p = ground ? Vector2d(0, 0) : Vector2d(q[pc], q[pc + 1]);
    const Vector2d rd_p = ground ? Vector2d(0, 0) : Vector2d(v[pc], v[pc + 1]);
    double x, xd, xdd, trig;
    edge_motion(m, e, t, theta, theta_dot, x, xd, xdd, trig);
    const bool rev = e.kind == TreeEdge::Kind::revolute, slide = e.kind == TreeEdge::Kind::slide;
    // A revolute's coordinate is its child's angle (see the header): no parent term.
    const double phi_c = rev ? x : phi_p + e.dphi;
    const double w_c = rev ? xd : w_p;
    // A slide or fixed joint without a relative angle keeps its parent's: the same angle,
    // the same cos and sin (no trigonometric call).
    // A body whose angle has not changed since the last call (the driven crank in the
    // Jacobian's difference quotients, any body in a velocity's) keeps its entries.
    // trig_phi holds the angle each body's cos and sin are of: a driven crank's phase, not
    // its φ after thousands of turns (edge_motion).
    const size_t ch = static_cast<size_t>(e.child);
    const double trig_c = rev ? trig : (ground ? 0.0 : k.trig_phi[static_cast<size_t>(e.parent)]) + e.dphi;
    if (!rev && e.dphi == 0.0) {
      k.cphi[ch] = cp;
      k.sphi[ch] = sp;
    } else if (k.trig_phi[ch] != trig_c) {
      k.cphi[ch] = std::cos(trig_c);
      k.sphi[ch] = std::sin(trig_c);
    }
    k.trig_phi[ch] = trig_c;
    const double cc_ = k.cphi[ch], sc = k.sphi[ch];
    auto Ap = [&](const Vector2d& s) { return Vector2d(cp * s.x() - sp * s.y(), sp * s.x() + cp * s.y()); };
    const Vector2d u = Ap(e.u_p);
    const Vector2d w = Ap(e.s_p) + (slide ? x * u : Vector2d(0, 0));
    const Vector2d ac(cc_ * e.s_c.x() - sc * e.s_c.y(), sc * e.s_c.x() + cc_ * e.s_c.y());
    const Vector2d r_c = r_p + w + e.o - ac;
    const Vector2d rd_c = rd_p + w_p * perp(w) + (slide ? xd * u : Vector2d(0, 0)) - w_c * perp(ac);
    q[cc] = r_c.x(), q[cc + 1] = r_c.y(), q[cc + 2] = phi_c;
    v[cc] = rd_c.x(), v[cc + 1] = rd_c.y(), v[cc + 2] = w_c;
    if (!derivatives) continue;
    // c: the acceleration with the free coordinates' θ̈ = 0.
    const double al_p = ground ? 0.0 : a[pc + 2];
    const Vector2d rdd_p = ground ? Vector2d(0, 0) : Vector2d(a[pc], a[pc + 1]);
    const double al_c = rev ? xdd : al_p;
    const Vector2d rdd_c = rdd_p + al_p * perp(w) - w_p * w_p * w +
                           (slide ? Vector2d(xdd * u + 2.0 * w_p * xd * perp(u)) : Vector2d(0, 0)) -
                           al_c * perp(ac) + w_c * w_c * ac;
    a[cc] = rdd_c.x(), a[cc + 1] = rdd_c.y(), a[cc + 2] = al_c;
    // J: the velocity map of each free coordinate's unit rate (the coordinates that move
    // this body; J's other entries on its rows stay zero).
    for (const int j : tree.edge_dofs[ei]) {
      const double jw_p = ground ? 0.0 : k.J(pc + 2, j);
      const Vector2d jr_p = ground ? Vector2d(0, 0) : Vector2d(k.J(pc, j), k.J(pc + 1, j));
      const double unit = e.dof == j ? 1.0 : 0.0;
      const double jw_c = rev ? unit : jw_p;
      const Vector2d jr_c = jr_p + jw_p * perp(w) + (slide ? Vector2d(unit * u) : Vector2d(0, 0)) - jw_c * perp(ac);
      k.J(cc, j) = jr_c.x();
      k.J(cc + 1, j) = jr_c.y();
      k.J(cc + 2, j) = jw_c;
    }
  }
}

void joint_coordinates(const Model& m, const JointTree& tree, const double* qv, double* theta,
                       double* theta_dot) {
  const double* q = qv;
  const double* v = qv + m.nq;
  for (const TreeEdge& e : tree.edges) {
    if (e.dof < 0) continue;
    if (e.kind == TreeEdge::Kind::free) {
      for (int i = 0; i < 3; ++i) {
        theta[e.dof + i] = q[3 * e.child + i];
        theta_dot[e.dof + i] = v[3 * e.child + i];
      }
      continue;
    }
    const BodyState p = body_state(e.parent, q, v), c = body_state(e.child, q, v);
    if (e.kind == TreeEdge::Kind::revolute) {
      theta[e.dof] = c.phi;
      theta_dot[e.dof] = c.phid;
      continue;
    }
    // Slide: P_c − P_p = θ A_p u_p (P_p = r_p + A_p s_p + o on the parent's side).
    const Vector2d u = p.rot(e.u_p), ap = p.rot(e.s_p), ac = c.rot(e.s_c);
    theta[e.dof] = u.dot(c.r + ac - p.r - ap - e.o);
    theta_dot[e.dof] = u.dot(c.rd + c.phid * perp(ac) - p.rd - p.phid * perp(ap));
  }
}

void joint_units(const Model& m, const JointTree& tree, const double* full, double* out) {
  const int nd = tree.ndof;
  for (const TreeEdge& e : tree.edges) {
    if (e.dof < 0) continue;
    if (e.kind == TreeEdge::Kind::free) {
      for (int i = 0; i < 3; ++i) {
        out[e.dof + i] = full[3 * e.child + i];
        out[nd + e.dof + i] = full[m.nq + 3 * e.child + i];
      }
      continue;
    }
    const int i = 3 * e.child + (e.kind == TreeEdge::Kind::revolute ? 2 : 0);
    out[e.dof] = full[i];
    out[nd + e.dof] = full[m.nq + i];
  }
}

}  // namespace lub
