// Blender's handle rules, restated for avar's keys (see handles.hpp). Blender works in frames
// and floats; every rule here is invariant under scaling time except the length of an aligned
// handle, which Blender measures in (frame, value) space: aligned handles that already continue
// the other side (as Blender saves them) are left where they are in any unit.
#include "avar/playback/offline/handles.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cfloat>
#include <cmath>

#include "avar/core/portable_math.hpp"

namespace avar::playback {
namespace {

struct Point {
  double x = 0, y = 0;
};
Point operator+(Point a, Point b) { return {a.x + b.x, a.y + b.y}; }
Point operator-(Point a, Point b) { return {a.x - b.x, a.y - b.y}; }
Point operator*(Point a, double f) { return {a.x * f, a.y * f}; }
double length(Point a) { return pmath::hypot(a.x, a.y); }

/// A key in Blender's form: left handle, key, right handle.
struct Triple {
  Point left, key, right;
  HandleType left_type = HandleType::free, right_type = HandleType::free;
  bool has_left = false, has_right = false;
  bool locked = false;  ///< Blender's auto_handle_type != HD_AUTOTYPE_NORMAL
};

bool is_auto(HandleType t) { return t == HandleType::automatic || t == HandleType::auto_clamped; }
bool fully_auto(const Triple& b) { return is_auto(b.left_type) && is_auto(b.right_type); }
bool free_auto_point(const Triple& b) { return fully_auto(b) && !b.locked; }

Triple shifted(const Triple& in, const Triple& from, const Triple& to) {
  Triple out = in;
  const Point delta = to.key - from.key;
  out.left = out.left + delta, out.key = out.key + delta, out.right = out.right + delta;
  return out;
}

// One key's handles from its neighbours (calchandleNurb_intern for F-curves).
void calc_handles(Triple& b, const Triple* prev, const Triple* next, bool smoothing) {
  b.locked = false;
  if (b.left_type == HandleType::free && b.right_type == HandleType::free) return;
  const Point p2 = b.key;
  const Point p1 = prev ? prev->key : p2 * 2 - next->key;
  const Point p3 = next ? next->key : p2 * 2 - p1;
  const Point da = p2 - p1, db = p3 - p2;
  double len_a = da.x == 0 ? 1 : da.x, len_b = db.x == 0 ? 1 : db.x;
  if (is_auto(b.left_type) || is_auto(b.right_type)) {
    const Point tvec = db * (1 / len_b) + da * (1 / len_a);
    const double len = (smoothing ? 6.0 / 2.5614 : tvec.x) * 2.5614;
    if (len != 0) {
      bool left_violate = false, right_violate = false;
      if (!smoothing) {
        if (len_a > 5 * len_b) len_a = 5 * len_b;
        if (len_b > 5 * len_a) len_b = 5 * len_a;
      }
      if (is_auto(b.left_type)) {
        b.left = p2 - tvec * (len_a / len);
        if (b.left_type == HandleType::auto_clamped && next && prev) {
          const double d1 = prev->key.y - p2.y, d2 = next->key.y - p2.y;
          if ((d1 <= 0 && d2 <= 0) || (d1 >= 0 && d2 >= 0)) {
            b.left.y = p2.y;
            b.locked = true;
          } else if (d1 <= 0 ? prev->key.y > b.left.y : prev->key.y < b.left.y) {
            b.left.y = prev->key.y;
            left_violate = true;
          }
        }
      }
      if (is_auto(b.right_type)) {
        b.right = p2 + tvec * (len_b / len);
        if (b.right_type == HandleType::auto_clamped && next && prev) {
          const double d1 = prev->key.y - p2.y, d2 = next->key.y - p2.y;
          if ((d1 <= 0 && d2 <= 0) || (d1 >= 0 && d2 >= 0)) {
            b.right.y = p2.y;
            b.locked = true;
          } else if (d1 <= 0 ? next->key.y < b.right.y : next->key.y > b.right.y) {
            b.right.y = next->key.y;
            right_violate = true;
          }
        }
      }
      if (left_violate || right_violate) {
        // Keep the pair collinear: the clamped side decides the slope.
        const double left_x = b.left.x - p2.x, right_x = p2.x - b.right.x;
        if (left_violate) b.right.y = p2.y + (p2.y - b.left.y) / left_x * right_x;
        else b.left.y = p2.y + (p2.y - b.right.y) / right_x * left_x;
      }
    }
  }
  if (b.left_type == HandleType::vector) b.left = p2 - da * (1.0 / 3.0);
  if (b.right_type == HandleType::vector) b.right = p2 + db * (1.0 / 3.0);

  if (b.left_type == HandleType::free || b.right_type == HandleType::free) return;
  if (b.left_type != HandleType::aligned && b.right_type != HandleType::aligned) return;
  double la = length(p2 - b.left), lb = length(p2 - b.right);
  if (la == 0) la = 1;
  if (lb == 0) lb = 1;
  constexpr double eps = 1e-5;
  // Blender's order with the left handle selected: the right side follows the left first.
  if (b.right_type == HandleType::aligned && la > eps) b.right = p2 + (p2 - b.left) * (lb / la);
  if (b.left_type == HandleType::aligned && lb > eps) b.left = p2 + (p2 - b.right) * (la / lb);
}

// Writes a smoothed handle height (bezier_output_handle): only auto and vector sides take it;
// an aligned opposite side turns to follow, and at the curve's ends an auto opposite mirrors it.
void output_handle(Triple& b, bool right, double dy, bool endpoint) {
  const HandleType own = right ? b.right_type : b.left_type;
  const HandleType other = right ? b.left_type : b.right_type;
  if (!is_auto(own) && own != HandleType::vector) return;
  Point& mine = right ? b.right : b.left;
  Point& theirs = right ? b.left : b.right;
  mine.y = b.key.y + dy;
  if (other == HandleType::aligned) {
    const double keep = length(b.key - theirs), now = length(b.key - mine);
    theirs = b.key + (b.key - mine) * (keep / now);
  } else if (endpoint && (is_auto(other) || other == HandleType::vector)) {
    theirs = b.key + (b.key - mine);
  }
}

// Cyclic tridiagonal system: a[i] h[i-1] + b[i] h[i] + c[i] h[i+1] = d[i], indices modulo n.
bool solve_cyclic_tridiagonal(const std::vector<double>& a, const std::vector<double>& b, const std::vector<double>& c,
                              const std::vector<double>& d, std::vector<double>& h) {
  const int n = static_cast<int>(b.size());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd rhs(n);
  for (int i = 0; i < n; ++i) {
    m(i, (i + n - 1) % n) += a[static_cast<std::size_t>(i)];
    m(i, i) += b[static_cast<std::size_t>(i)];
    m(i, (i + 1) % n) += c[static_cast<std::size_t>(i)];
    rhs(i) = d[static_cast<std::size_t>(i)];
  }
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(m);
  if (!lu.isInvertible()) return false;
  const Eigen::VectorXd x = lu.solve(rhs);
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(x(i))) return false;
    h[static_cast<std::size_t>(i)] = x(i);
  }
  return true;
}

struct System {
  std::vector<double> a, b, c, d;
  void lock(std::size_t i, double value) { a[i] = c[i] = 0, b[i] = 1, d[i] = value; }
};

// tridiagonal_solve_with_limits: solve, lock handles beyond their clamp range, release locked
// ones that want to move back inside (at most twice each), until nothing changes.
bool solve_with_limits(System s, std::vector<double>& h, const std::vector<double>& hmin, const std::vector<double>& hmax) {
  const System original = s;
  const std::size_t n = s.b.size();
  std::vector<bool> is_locked(n, false);
  std::vector<int> unlocks(n, 0);
  bool overshoot = false, unlocked = false;
  int rounds = 0;
  do {
    // Each round locks or releases at least one handle and releases are limited, so this ends;
    // the cap only guards against rounding making a locked handle look out of range.
    if (++rounds > 4 * static_cast<int>(n) + 8) return true;
    if (!solve_cyclic_tridiagonal(s.a, s.b, s.c, s.d, h)) return false;
    for (std::size_t i = 0; i < n; ++i)
      if (is_locked[i]) h[i] = s.d[i];  // a locked row reads h[i] = d[i], exactly
    bool all = false, locked = false;
    overshoot = unlocked = false;
    do {
      for (std::size_t i = 0; i < n; ++i) {
        if (h[i] >= hmin[i] && h[i] <= hmax[i]) continue;
        overshoot = true;
        const double target = h[i] > hmax[i] ? hmax[i] : hmin[i];
        if (target != 0 || all) {
          is_locked[i] = true;
          s.lock(i, target);
          locked = true;
        }
      }
      all = true;
    } while (overshoot && !locked);
    if (!locked) {
      for (std::size_t i = 0; i < n; ++i) {
        if (!is_locked[i] || unlocks[i] >= 2) continue;
        const double state =
            original.a[i] * h[(i + n - 1) % n] + original.b[i] * h[i] + original.c[i] * h[(i + 1) % n] - original.d[i];
        const double relax = -state * original.b[i];
        if ((relax > 0 && h[i] < hmax[i]) || (relax < 0 && h[i] > hmin[i])) {
          s.a[i] = original.a[i], s.b[i] = original.b[i], s.c[i] = original.c[i], s.d[i] = original.d[i];
          is_locked[i] = false;
          ++unlocks[i];
          unlocked = true;
        }
      }
    }
  } while (overshoot || unlocked);
  return true;
}

void clamp_range(std::vector<double>& hmax, std::vector<double>& hmin, std::size_t i, double dy, bool clamped) {
  if (!clamped) return;
  if (dy > 0) {
    hmax[i] = std::min(hmax[i], dy);
    hmin[i] = 0;
  } else if (dy < 0) {
    hmax[i] = 0;
    hmin[i] = std::max(hmin[i], dy);
  } else {
    hmax[i] = hmin[i] = 0;
  }
}

double handle_adjustment(Point& size, double dx) {
  const double fac = dx / (size.x + dx / 3);
  if (fac < 1) size = size * fac;
  return 1 - 3 * size.x / dx;
}

bool is_clamped(const Triple& b) { return b.left_type == HandleType::auto_clamped || b.right_type == HandleType::auto_clamped; }

// Continuous-acceleration smoothing of `count` keys from `start` (bezier_handle_calc_smooth_fcurve).
// With `cycle`, index total - 1 is the same key as 0 and runs may wrap around.
void smooth_run(std::vector<Triple>& k, int total, int start, int count, bool cycle) {
  if (count < 2) return;
  const auto at = [&](int j) -> Triple& { return k[static_cast<std::size_t>(j)]; };
  const bool full_cycle = start == 0 && count == total && cycle;
  Triple& first = at(start);
  Triple& last = at(start + count > total ? start + count - total : start + count - 1);
  const auto solve_end = [](const Triple& b, HandleType type, bool end) {
    return type == HandleType::vector || (end && is_auto(type) && !b.locked);
  };
  bool solve_first = solve_end(first, first.right_type, start == 0);
  bool solve_last = solve_end(last, last.left_type, start + count == total);
  if (count == 2 && !full_cycle && solve_first == solve_last) return;

  const auto n = static_cast<std::size_t>(count);
  std::vector<double> dx(n), dy(n), l(n), h(n), hmax(n, DBL_MAX), hmin(n, -DBL_MAX);
  for (int i = 1, j = start + 1; i < count; ++i, ++j) {
    dx[static_cast<std::size_t>(i)] = at(j).key.x - at(j - 1).key.x;
    dy[static_cast<std::size_t>(i)] = at(j).key.y - at(j - 1).key.y;
    if (cycle && j == total - 1) j = 0;
  }
  if (full_cycle) {
    dx[0] = dx[n - 1], dy[0] = dy[n - 1];
    l[0] = l[n - 1] = dx[1] / dx[0];
  } else {
    l[0] = l[n - 1] = 1;
  }
  for (std::size_t i = 1; i + 1 < n; ++i) l[i] = dx[i + 1] / dx[i];

  bool clamped_cur = is_clamped(first);
  for (int i = 1, j = start + 1; i < count; ++i, ++j) {
    const bool clamped_prev = clamped_cur;
    clamped_cur = is_clamped(at(j));
    if (cycle && j == total - 1) {
      j = 0;
      clamped_cur = clamped_cur || is_clamped(at(j));
    }
    const auto u = static_cast<std::size_t>(i);
    clamp_range(hmax, hmin, u - 1, dy[u], clamped_prev);
    clamp_range(hmax, hmin, u, dy[u] * l[u], clamped_cur);
  }

  std::size_t solve_count = n;
  System s{std::vector<double>(n), std::vector<double>(n), std::vector<double>(n), std::vector<double>(n)};
  const auto continuous = [&](std::size_t i) {
    s.a[i] = l[i] * l[i], s.b[i] = 2 * (l[i] + 1), s.c[i] = 1 / l[i + 1], s.d[i] = dy[i] * l[i] * l[i] + dy[i + 1];
  };
  double first_adj = 0, last_adj = 0;
  if (full_cycle) {
    solve_count = n - 1;
    hmin[0] = std::max(hmin[0], hmin[solve_count]);
    hmax[0] = std::min(hmax[0], hmax[solve_count]);
    solve_first = solve_last = true;
    continuous(0);
  } else {
    if (!solve_first) {
      Point size = first.right - first.key;
      first_adj = handle_adjustment(size, dx[1]);
      s.lock(0, size.y);
    } else {
      s.a[0] = 0, s.b[0] = 2, s.c[0] = 1 / l[1], s.d[0] = dy[1];
    }
    if (!solve_last) {
      Point size = last.key - last.left;
      last_adj = handle_adjustment(size, dx[n - 1]);
      s.lock(n - 1, size.y);
    } else {
      s.a[n - 1] = l[n - 1] * l[n - 1], s.b[n - 1] = 2 * l[n - 1], s.c[n - 1] = 0, s.d[n - 1] = dy[n - 1] * l[n - 1] * l[n - 1];
    }
  }
  for (std::size_t i = 1; i + 1 < n; ++i) continuous(i);
  if (!full_cycle) {
    if (count > 2 || solve_last) s.b[1] += l[1] * first_adj;
    if (count > 2 || solve_first) s.b[n - 2] += last_adj;
  }
  for (auto* v : {&s.a, &s.b, &s.c, &s.d}) v->resize(solve_count);
  std::vector<double> hs(solve_count), lo(hmin.begin(), hmin.begin() + static_cast<std::ptrdiff_t>(solve_count)),
      hi(hmax.begin(), hmax.begin() + static_cast<std::ptrdiff_t>(solve_count));
  if (!solve_with_limits(s, hs, lo, hi)) return;
  std::copy(hs.begin(), hs.end(), h.begin());
  if (full_cycle) h[n - 1] = h[0];
  for (int i = 1, j = start + 1; i < count - 1; ++i, ++j) {
    const auto u = static_cast<std::size_t>(i);
    const bool end = j == total - 1;
    output_handle(at(j), false, -h[u] / l[u], end);
    if (end) j = 0;
    output_handle(at(j), true, h[u], end);
  }
  if (solve_first) output_handle(first, true, h[0], start == 0);
  if (solve_last) output_handle(last, false, -h[n - 1] / l[n - 1], start + count == total);
}

void smooth(std::vector<Triple>& k, bool cyclic) {
  const int total = static_cast<int>(k.size());
  cyclic = cyclic && free_auto_point(k.front()) && free_auto_point(k.back());
  int base = 0;
  if (cyclic) {
    for (int i = 1; i < total - 1; ++i)
      if (!free_auto_point(k[static_cast<std::size_t>(i)])) {
        base = i;
        break;
      }
    if (base == 0) {
      smooth_run(k, total, 0, total, cyclic);
      return;
    }
  }
  int start = base, count = 1;
  for (int i = 1, j = start + 1; i < total; ++i, ++j) {
    if (j == total - 1 && cyclic) j = 0;
    if (!free_auto_point(k[static_cast<std::size_t>(j)])) {
      smooth_run(k, total, start, count + 1, cyclic);
      start = j;
      count = 1;
    } else {
      ++count;
    }
  }
  if (count > 1) smooth_run(k, total, start, count, cyclic);
}

}  // namespace

HandleType left_type_of(const RawKey& key) noexcept {
  return key.left_type ? *key.left_type : key.left ? HandleType::free : HandleType::auto_clamped;
}
HandleType right_type_of(const RawKey& key) noexcept {
  return key.right_type ? *key.right_type : key.right ? HandleType::free : HandleType::auto_clamped;
}

bool cyclic_for_handles(const Cycles& c) noexcept {
  const auto repeats = [](CycleMode m) { return m == CycleMode::repeat || m == CycleMode::repeat_offset; };
  return c.before_count == 0 && c.after_count == 0 && repeats(c.before) && repeats(c.after);
}

std::vector<ResolvedHandles> compute_handles(const RawCurve& raw) {
  std::vector<Triple> k;
  k.reserve(raw.keys.size());
  for (const RawKey& key : raw.keys) {
    Triple b;
    b.key = {key.time, key.value};
    b.left_type = left_type_of(key);
    b.right_type = right_type_of(key);
    b.has_left = key.left.has_value() || b.left_type != HandleType::free;
    b.has_right = key.right.has_value() || b.right_type != HandleType::free;
    b.left = key.left ? Point{key.left->time, key.left->value} : b.key;
    b.right = key.right ? Point{key.right->time, key.right->value} : b.key;
    k.push_back(b);
  }
  const std::size_t n = k.size();
  if (n >= 2) {
    const bool smoothing = raw.auto_smoothing != AutoSmoothing::none;
    const bool cycle = cyclic_for_handles(raw.cycles) && fully_auto(k.front()) && fully_auto(k.back());
    std::optional<Triple> wrapped;
    if (cycle) wrapped = shifted(k[n - 2], k[n - 1], k[0]);
    for (std::size_t i = 0; i < n; ++i) {
      Triple& b = k[i];
      // Handles may not cross their key in time (free handles are taken as given).
      if (b.left_type != HandleType::free) b.left.x = std::min(b.left.x, b.key.x);
      if (b.right_type != HandleType::free) b.right.x = std::max(b.right.x, b.key.x);
      const Triple* prev = i > 0 ? &k[i - 1] : wrapped ? &*wrapped : nullptr;
      std::optional<Triple> next_wrapped;
      if (i + 1 == n && cycle) next_wrapped = shifted(k[1], k[0], k[n - 1]);
      const Triple* next = i + 1 < n ? &k[i + 1] : next_wrapped ? &*next_wrapped : nullptr;
      calc_handles(b, prev, next, smoothing);
      if (fully_auto(b) && !cycle && (i == 0 || i + 1 == n) && raw.extrapolation == Extrapolation::constant) {
        b.left.y = b.right.y = b.key.y;
        b.locked = true;
      }
    }
    if (cycle && (k.front().locked || k.back().locked)) {
      for (Triple* b : {&k.front(), &k.back()}) {
        b->left.y = b->right.y = b->key.y;
        b->locked = true;
      }
    }
    if (smoothing) smooth(k, cycle);
  }
  std::vector<ResolvedHandles> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i].left_type = k[i].left_type;
    out[i].right_type = k[i].right_type;
    if (k[i].has_left) out[i].left = Handle{k[i].left.x, k[i].left.y};
    if (k[i].has_right) out[i].right = Handle{k[i].right.x, k[i].right.y};
  }
  return out;
}

}  // namespace avar::playback
