#pragma once
// The Bezier maths of Blender's F-curves (blenkernel fcurve.cc), as avar's curves use it:
// - handle correction (BKE_fcurve_correct_bezpart): neither handle of a segment may reach further
//   in time than the segment is long;
// - the time solve (findzero / solve_cubic): the time of a segment is the cubic
//   x(u) = c0 + c1 u + c2 u^2 + c3 u^3 in the curve parameter u; for a sample time the roots of
//   x(u) - time are found in closed form and the FIRST one that Blender's window accepts is used,
//   which decides the shape when handles make time run backwards;
// - the value cubic (berekeny) evaluated at that parameter.
// Every function here is pure: no allocation, no exception, no shared state, so it is real-time
// safe and may be called from any thread.

namespace avar::playback {

/// Coefficients of a cubic c0 + c1 u + c2 u^2 + c3 u^3.
struct Cubic {
  double c0 = 0, c1 = 0, c2 = 0, c3 = 0;
  double at(double u) const noexcept { return c0 + u * (c1 + u * (c2 + u * c3)); }
  /// First derivative with respect to u.
  double slope_at(double u) const noexcept { return c1 + u * (2.0 * c2 + u * 3.0 * c3); }
};

/// The power-basis form of the Bezier with control points p[0..3] along one axis:
/// c0 = p0, c1 = 3(p1 - p0), c2 = 3(p0 - 2 p1 + p2), c3 = p3 - p0 + 3(p1 - p2).
Cubic bezier_polynomial(const double p[4]) noexcept;

/// Blender's handle correction for one segment, in place. time[0], value[0]: the start key;
/// [1]: its right handle; [2]: the end key's left handle; [3]: the end key (seconds, channel
/// units). A handle whose time extent |handle time - key time| exceeds the segment length
/// time[3] - time[0] is scaled towards its key by length / extent, time and value alike, so it
/// keeps its direction and ends exactly one segment length away in time. Handles that point the
/// wrong way (a right handle before its key) keep pointing that way, as in Blender.
/// Precondition: time[3] > time[0].
void correct_bezier_handles(double time[4], double value[4]) noexcept;

/// Roots of c0 + c1 u + c2 u^2 + c3 u^3 = 0 that Blender accepts (rounded to float, within
/// [-1e-10, 1.000001]), in Blender's order: a cubic with one real root gives it; one with three
/// distinct real roots gives the largest, then the smallest, then the middle one; a quadratic
/// gives (-c1 - sqrt(D)) / (2 c2) before (-c1 + sqrt(D)) / (2 c2). Writes up to 3 roots, returns
/// how many. The same roots as Blender's formula, computed without its cancellations (see the
/// source); a cubic term that is negligible against the others (|c3| <= 1e-9 (|c1| + |c2|)), which
/// rounding leaves where handles sit at thirds, is treated as zero.
int solve_cubic_in_unit_interval(double c0, double c1, double c2, double c3, double roots[3]) noexcept;

/// Curve parameter u at which the Bezier whose time control points are q[0..3] reaches time x:
/// Blender's first accepted root, or a negative value when there is none.
double bezier_parameter_at_time(double x, const double q[4]) noexcept;

/// Value at parameter u of the Bezier with control values f[0..3].
double bezier_value(const double f[4], double u) noexcept;

}  // namespace avar::playback
