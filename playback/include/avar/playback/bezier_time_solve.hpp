#pragma once
// The cubic solve Blender uses to turn a time on a Bezier segment into the curve parameter:
// roots of c0 + c1 u + c2 u^2 + c3 u^3 = 0 in [0, 1] (with Blender's tolerances), found in
// closed form, in Blender's order, so that where several roots exist the same one is chosen.
// Real-time safe.

namespace avar::playback {

/// Writes up to 3 roots within [-1e-10, 1.000001] to `roots`, in Blender's order; returns how
/// many.
int solve_cubic_in_unit_interval(double c0, double c1, double c2, double c3, double roots[3]) noexcept;

/// Parameter u in [0, 1] at which the Bezier with time control points q0..q3 reaches time x,
/// or a negative value when there is none.
double bezier_parameter_at_time(double x, const double q[4]) noexcept;

/// Value of the cubic Bezier with control values f[0..3] at parameter u.
double bezier_value(const double f[4], double u) noexcept;

}  // namespace avar::playback
