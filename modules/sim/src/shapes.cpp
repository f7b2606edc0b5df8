#include "gasp/sim/shapes.h"

#include <array>
#include <cmath>
#include <limits>

namespace gasp::sim {

namespace {

constexpr double kParallelEps = 1e-12;

/// Slab test of the box |p| <= h. t_near/t_far and their faces (0..5 = -x,+x,-y,+y,-z,+z).
bool slabs(const Eigen::Vector3d& h, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
           double& t_near, int& f_near, double& t_far, int& f_far) {
  t_near = -std::numeric_limits<double>::infinity();
  t_far = std::numeric_limits<double>::infinity();
  f_near = f_far = -1;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < kParallelEps) {
      if (std::abs(o[a]) > h[a]) return false;
      continue;
    }
    const double t_lo = (-h[a] - o[a]) / d[a];
    const double t_hi = (h[a] - o[a]) / d[a];
    const bool positive = d[a] > 0.0;
    const double tn = positive ? t_lo : t_hi;
    const double tf = positive ? t_hi : t_lo;
    if (tn > t_near) {
      t_near = tn;
      f_near = 2 * a + (positive ? 0 : 1);
    }
    if (tf < t_far) {
      t_far = tf;
      f_far = 2 * a + (positive ? 1 : 0);
    }
  }
  return t_near <= t_far;
}

Eigen::Vector3d outwardBoxNormal(int face) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[face / 2] = (face % 2 == 0) ? -1.0 : 1.0;
  return n;
}

/// Real roots of a t^2 + b t + c = 0 in ascending order; returns their number (0 or 2).
int quadraticRoots(double a, double b, double c, std::array<double, 2>& roots) {
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0 || std::abs(a) < kParallelEps) return 0;
  const double s = std::sqrt(disc);
  // Numerically stable form.
  const double q = -0.5 * (b + (b >= 0.0 ? s : -s));
  double r0 = q / a;
  double r1 = (q != 0.0) ? c / q : r0;
  if (r0 > r1) std::swap(r0, r1);
  roots = {r0, r1};
  return 2;
}

}  // namespace

bool intersect(const Rectangle& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
               double t_min, RayHit& hit) {
  if (std::abs(d.z()) < kParallelEps) return false;
  const double t = -o.z() / d.z();
  if (!(t > t_min)) return false;
  const Eigen::Vector3d p = o + t * d;
  if (std::abs(p.x()) > s.half_x || std::abs(p.y()) > s.half_y) return false;
  hit.t = t;
  hit.normal = Eigen::Vector3d::UnitZ();
  hit.face = 0;
  return true;
}

bool intersect(const Box& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min,
               RayHit& hit) {
  double tn = 0.0, tf = 0.0;
  int fn = -1, ff = -1;
  if (!slabs(s.half_extents, o, d, tn, fn, tf, ff)) return false;
  if (tn > t_min && fn >= 0) {
    hit = {tn, outwardBoxNormal(fn), fn};
    return true;
  }
  if (tf > t_min && ff >= 0) {  // the ray starts inside the box: its exit face
    hit = {tf, outwardBoxNormal(ff), ff};
    return true;
  }
  return false;
}

bool intersect(const Room& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min,
               RayHit& hit) {
  double tn = 0.0, tf = 0.0;
  int fn = -1, ff = -1;
  if (!slabs(s.half_extents, o, d, tn, fn, tf, ff)) return false;
  if (!(tf > t_min) || ff < 0) return false;
  hit = {tf, -outwardBoxNormal(ff), ff};
  return true;
}

bool intersect(const Cylinder& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
               double t_min, RayHit& hit) {
  bool found = false;
  double best = std::numeric_limits<double>::infinity();
  // Side: (ox + t dx)^2 + (oy + t dy)^2 = r^2 with |z| <= half_height.
  std::array<double, 2> roots{};
  const int n = quadraticRoots(d.x() * d.x() + d.y() * d.y(), 2.0 * (o.x() * d.x() + o.y() * d.y()),
                               o.x() * o.x() + o.y() * o.y() - s.radius * s.radius, roots);
  for (int i = 0; i < n; ++i) {
    const double t = roots[static_cast<std::size_t>(i)];
    if (!(t > t_min)) continue;
    const Eigen::Vector3d p = o + t * d;
    if (std::abs(p.z()) > s.half_height) continue;
    best = t;
    hit = {t, Eigen::Vector3d(p.x(), p.y(), 0.0).normalized(), 0};
    found = true;
    break;
  }
  // Caps.
  if (std::abs(d.z()) >= kParallelEps) {
    for (int cap = 1; cap <= 2; ++cap) {
      const double zc = cap == 1 ? -s.half_height : s.half_height;
      const double t = (zc - o.z()) / d.z();
      if (!(t > t_min) || t >= best) continue;
      const Eigen::Vector3d p = o + t * d;
      if (p.x() * p.x() + p.y() * p.y() > s.radius * s.radius) continue;
      best = t;
      hit = {t, Eigen::Vector3d(0.0, 0.0, cap == 1 ? -1.0 : 1.0), cap};
      found = true;
    }
  }
  return found;
}

bool intersect(const Sphere& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min,
               RayHit& hit) {
  std::array<double, 2> roots{};
  const int n = quadraticRoots(d.squaredNorm(), 2.0 * o.dot(d), o.squaredNorm() - s.radius * s.radius,
                               roots);
  for (int i = 0; i < n; ++i) {
    const double t = roots[static_cast<std::size_t>(i)];
    if (!(t > t_min)) continue;
    hit = {t, (o + t * d) / s.radius, 0};
    hit.normal.normalize();
    return true;
  }
  return false;
}

bool intersect(const Shape& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_min,
               RayHit& hit) {
  return std::visit([&](const auto& shape) { return intersect(shape, o, d, t_min, hit); }, s);
}

namespace {
template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;
}  // namespace

int faceCount(const Shape& s) {
  return std::visit(Overloaded{[](const Rectangle&) { return 1; }, [](const Box&) { return 6; },
                               [](const Cylinder&) { return 3; }, [](const Sphere&) { return 1; },
                               [](const Room&) { return 6; }},
                    s);
}

double boundingRadius(const Shape& s) {
  return std::visit(
      Overloaded{[](const Rectangle& r) { return std::hypot(r.half_x, r.half_y); },
                 [](const Box& b) { return b.half_extents.norm(); },
                 [](const Cylinder& c) { return std::hypot(c.radius, c.half_height); },
                 [](const Sphere& sp) { return sp.radius; },
                 [](const Room&) { return std::numeric_limits<double>::infinity(); }},
      s);
}

std::string shapeTypeName(const Shape& s) {
  return std::visit(
      Overloaded{[](const Rectangle&) { return std::string("rectangle"); },
                 [](const Box&) { return std::string("box"); },
                 [](const Cylinder&) { return std::string("cylinder"); },
                 [](const Sphere&) { return std::string("sphere"); },
                 [](const Room&) { return std::string("room"); }},
      s);
}

std::string faceName(const Shape& s, int face) {
  static const std::array<const char*, 6> box_faces{"-x", "+x", "-y", "+y", "-z", "+z"};
  static const std::array<const char*, 6> room_faces{"wall-x", "wall+x", "wall-y",
                                                     "wall+y", "floor",  "ceiling"};
  static const std::array<const char*, 3> cylinder_faces{"side", "bottom", "top"};
  if (face < 0 || face >= faceCount(s)) return "?";
  const auto i = static_cast<std::size_t>(face);
  return std::visit(
      Overloaded{[](const Rectangle&) { return std::string("plane"); },
                 [&](const Box&) { return std::string(box_faces[i]); },
                 [&](const Cylinder&) { return std::string(cylinder_faces[i]); },
                 [](const Sphere&) { return std::string("surface"); },
                 [&](const Room&) { return std::string(room_faces[i]); }},
      s);
}

}  // namespace gasp::sim
