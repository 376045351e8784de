// The lubricated joint's film: exuclear/film/ (laws.py, loads.py) (docs/physics.md section 10, eqs. (55)-(70)).
// Python: exuclear/engine/_python_kernel/film.py.

#pragma once

#include "contacts.hpp"

namespace {

// ---- the film: film.py (docs/physics.md section 10, eqs. (55)-(70)) ------------------------------
// film.py FilmInput (_python_kernel/film.py): e in the bearing's joint frame, de/dt as the connector
// hands it over (the inertial derivative in that frame's components), the absolute spins.
struct FilmInput {
    double ex, ey, vx, vy, omega_journal, omega_bearing;
};

struct FilmKinematics {  // film.py FilmKinematics, eq. (56)
    double eps, eps_dot, omega_eff, nx, ny;
};

struct FilmLoad {  // film.py FilmLoad: force on the journal, moments on journal and bearing, eqs. (68)-(69)
    double fx, fy, torque_journal, torque_bearing;
};

FilmKinematics film_kinematics(const FilmInput& in, double clearance) {  // eqs. (55)-(56)
    double ecc = std::sqrt(in.ex * in.ex + in.ey * in.ey);
    double nx, ny, phi_dot;
    if (ecc > 0.0) {
        nx = in.ex / ecc;
        ny = in.ey / ecc;
        phi_dot = (in.ex * in.vy - in.ey * in.vx) / (ecc * ecc);
    } else {  // centred: the normal along de/dt, or (1, 0) at rest
        double speed = std::sqrt(in.vx * in.vx + in.vy * in.vy);
        nx = speed > 0.0 ? in.vx / speed : 1.0;
        ny = speed > 0.0 ? in.vy / speed : 0.0;
        phi_dot = 0.0;
    }
    double eps_dot = (nx * in.vx + ny * in.vy) / clearance;
    return FilmKinematics{ecc / clearance, eps_dot, in.omega_journal + in.omega_bearing - 2.0 * phi_dot, nx, ny};
}

// film.py blend_eccentricity, eq. (70): the eccentricity ratio (and rate) the film is evaluated at
void blend_eccentricity(double eps, double eps_dot, double eps_film, double eps_cap, double& eps_b,
                        double& eps_dot_b) {
    if (eps <= eps_film) {
        eps_b = eps;
        eps_dot_b = eps_dot;
        return;
    }
    double width = eps_cap - eps_film;
    double x = (eps - eps_film) / width;
    double q = std::exp(-2.0 * x);  // tanh(x) = (1 - q) / (1 + q), 1 / cosh^2(x) = 4 q / (1 + q)^2: one exp
    eps_b = eps_film + width * ((1.0 - q) / (1.0 + q));
    eps_dot_b = eps_dot * (4.0 * q / ((1.0 + q) * (1.0 + q)));
}

// ShortBearing.components, eqs. (58)-(60): the positive part of Ocvirk's pressure.  Its sign in
// gamma is a0 + a1 cos + b1 sin with a0 = 2 eps_dot eps, a1 = -2 eps_dot, b1 = rot, positive on
// one arc (phase - half, phase + half) around the phase of (a1, b1), cos(half) = -a0 / |(a1, b1)|
// (film.py ShortBearing._arc, the same steps).  The antiderivatives
// g_n, g_t of film.py are evaluated between its ends from their cosines and sines, which follow
// from (a0, a1, b1) without trigonometric calls; only the arc's length needs acos.
void short_components(const Params& a, double clearance, double eps, double eps_dot, double omega_eff, double& f_n,
                      double& f_perp) {
    double s = std::sqrt(1.0 - eps * eps);
    double rot = eps * omega_eff * s;
    double a0 = 2.0 * eps_dot * eps, a1 = -2.0 * eps_dot, b1 = rot;
    double amplitude = std::sqrt(a1 * a1 + b1 * b1);
    // the arc's ends x1 < x2 by cosine and sine, and its length
    double c1 = 1.0, s1 = 0.0, c2 = 1.0, s2 = 0.0, length = 0.0;
    if (a0 >= amplitude) {
        if (a0 > 0.0) length = 2.0 * M_PI;  // positive everywhere: the whole circle
    } else if (a0 > -amplitude) {
        double cp = a1 / amplitude, sp = b1 / amplitude;    // phase
        double ch = -a0 / amplitude;                         // cos(half)
        double sh = std::sqrt(1.0 - ch * ch);                // sin(half) >= 0
        c1 = cp * ch + sp * sh;
        s1 = sp * ch - cp * sh;
        c2 = cp * ch - sp * sh;
        s2 = sp * ch + cp * sh;
        length = 2.0 * std::acos(ch);
    }
    double d_cos = c2 - c1, d_sin = s2 - s1;
    double d_cos2 = (c2 * c2 - s2 * s2) - (c1 * c1 - s1 * s1);  // cos(2 x2) - cos(2 x1)
    double d_sin2 = 2.0 * (s2 * c2 - s1 * c1);                  // sin(2 x2) - sin(2 x1)
    // g_n: antiderivative of (rot sin - 2 eps_dot (cos - eps)) (cos - eps)
    double in_n = (rot * (-0.25 * d_cos2 + eps * d_cos)
                   - 2.0 * eps_dot * ((0.5 + eps * eps) * length + 0.25 * d_sin2 - 2.0 * eps * d_sin));
    // g_t: antiderivative of (rot sin - 2 eps_dot (cos - eps)) sin
    double in_t = rot * (0.5 * length - 0.25 * d_sin2) - 2.0 * eps_dot * (-0.25 * d_cos2 + eps * d_cos);
    double scale = a.viscosity * a.length * a.length * a.length * a.r_j / (2.0 * clearance * clearance);  // eq. (60)
    double s2_ = s * s;
    f_n = scale * in_n / (s2_ * s2_ * s);
    f_perp = scale * in_t / (s2_ * s2_);
}

// LongBearing._arc (film.py): the arc of positive pressure of the long bearing (docs/physics.md section
// 10.2, eqs. (62a)-(62c)).  Its sign in gamma is g = a0 + a1 cos + b1 sin + a2 cos 2x + b2 sin 2x (a1 =
// sigma q1 enters only through g(0) and g(pi), below), which,
// unless the squeeze sigma is 0, has exactly two zeros, both simple: one in (0, pi) and one in (pi, 2 pi)
// (g(0) = -sigma (1 - eps)^2 (4 - eps), g(pi) = sigma (1 + eps)^2 (4 + eps)).  The positive part is one
// arc: from the first zero to the second for sigma > 0 (around the smallest gap), from the second to the
// first (plus 2 pi) for sigma < 0.  With tau = tan(gamma / 2), (1 + tau^2)^2 g is the quartic
// k0 + k1 tau + ... + k4 tau^4 (eq. (62b)); the sign of g at pi/2 (or 3 pi/2) tells which quarter
// circle holds each zero, and there it is the only root in [0, 1] of the quartic in t = |tau| or
// u = 1 / |tau|, found by Halley's iteration (QuarticRoot).  A pure function of (eps, eps_dot, omega_eff).
struct Arc {
    double c1, s1, c2, s2, length;  // cos and sin of its ends gamma_1 < gamma_2, and gamma_2 - gamma_1
};

// Halley's iteration converges cubically: once a step is below ROOT_RTOL of the root, what is left is
// of the order of its cube, round-off (measured: at most 4e-16 relative).  A step that leaves the
// bracket is replaced by bisection; ROOT_ITERATIONS is far more than needed (4 on average).
const double ROOT_RTOL = 1e-6;
const int ROOT_ITERATIONS = 100;

// film.py _root_in_unit_interval: the root in [0, 1] of p = k0 + k1 x + k2 x^2 + k3 x^3 + k4 x^4, given
// p(1) = p_one of the sign opposite to k0's (or 0), from the secant's root.  One step at a time, so that
// the arc's two roots iterate side by side (independent: the processor overlaps them).
struct QuarticRoot {
    double k[5], lo, hi, x;
    bool done;
    QuarticRoot(double k0, double k1, double k2, double k3, double k4, double p_one)
        : k{k0, k1, k2, k3, k4}, lo(0.0), hi(1.0), x(p_one == 0.0 ? 1.0 : k0 / (k0 - p_one)), done(p_one == 0.0) {}
    void step() {
        double x2 = x * x;  // p, p', p'' in Estrin's order: shorter chains of dependent operations than Horner's
        double p = (k[0] + k[1] * x) + (k[2] + k[3] * x) * x2 + k[4] * (x2 * x2);
        double dp = (k[1] + 2.0 * k[2] * x) + (3.0 * k[3] + 4.0 * k[4] * x) * x2;
        double ddp = 2.0 * k[2] + (6.0 * k[3] + 12.0 * k[4] * x) * x;
        if (p == 0.0) {
            done = true;
            return;
        }
        if ((p > 0.0) == (k[0] > 0.0)) {
            lo = x;
        } else {
            hi = x;
        }
        double den = dp * dp - 0.5 * p * ddp;
        double next = den != 0.0 ? x - p * dp / den : -1.0;
        bool halley = next >= lo && next <= hi;
        if (!halley) next = 0.5 * (lo + hi);  // the step left the bracket: bisect
        double change = std::fabs(next - x);
        x = next;
        done = halley && change <= ROOT_RTOL * x;
    }
};

// film.py LongBearing._arc: the positive arc at eps, with rho = eps omega_eff s / (2 + eps^2) and the
// squeeze factor sigma = eps_dot / (2 + 3 eps^2)
Arc long_arc(double eps, double rho, double sigma) {
    if (sigma == 0.0) {  // rotation alone: g = rho sin (2 - eps^2 - eps cos), zero at 0 and pi
        if (rho > 0.0) return Arc{1.0, 0.0, -1.0, 0.0, M_PI};
        if (rho < 0.0) return Arc{-1.0, 0.0, 1.0, 0.0, M_PI};
        return Arc{1.0, 0.0, 1.0, 0.0, 0.0};  // no film pressure at all
    }
    // sign of p in gamma (eq. (62a)): rho sin (2 - eps^2 - eps cos) + sigma (q0 + q1 cos + q2 cos^2)
    double eps3 = eps * eps * eps;
    double q0 = 7.0 * eps - 2.0 * eps3, q2 = 2.0 * eps + 3.0 * eps3;
    double a0 = sigma * (q0 + 0.5 * q2), b1 = rho * (2.0 - eps * eps), a2 = 0.5 * sigma * q2, b2 = -0.5 * rho * eps;
    // eq. (62b); k0 = g(0) and k4 = g(pi) in their factored forms, whose signs are exact
    double k0 = -sigma * (1.0 - eps) * (1.0 - eps) * (4.0 - eps), k1 = 2.0 * b1 + 4.0 * b2, k2 = 2.0 * a0 - 6.0 * a2,
           k3 = 2.0 * b1 - 4.0 * b2, k4 = sigma * (1.0 + eps) * (1.0 + eps) * (4.0 + eps);
    // the zero in (0, pi): in (0, pi/2) (tau = t) where g(pi/2) has the sign of g(pi), else in [pi/2, pi) (tau = 1 / u)
    double q_plus = k0 + k1 + k2 + k3 + k4;  // 4 g(pi/2)
    bool first_t = (q_plus > 0.0) != (k0 > 0.0) && q_plus != 0.0;
    QuarticRoot first = first_t ? QuarticRoot(k0, k1, k2, k3, k4, q_plus) : QuarticRoot(k4, k3, k2, k1, k0, q_plus);
    // the zero in (pi, 2 pi): in (3 pi/2, 2 pi) (tau = -t) where g(3 pi/2) has the sign of g(pi), else in
    // (pi, 3 pi/2] (tau = -1 / u)
    double q_minus = k0 - k1 + k2 - k3 + k4;  // 4 g(3 pi/2)
    bool second_t = (q_minus > 0.0) != (k0 > 0.0) && q_minus != 0.0;
    QuarticRoot second = second_t ? QuarticRoot(k0, -k1, k2, -k3, k4, q_minus) : QuarticRoot(k4, -k3, k2, -k1, k0, q_minus);
    for (int it = 0; it < ROOT_ITERATIONS && !(first.done && second.done); ++it) {
        if (!first.done) first.step();
        if (!second.done) second.step();
    }
    // the ends from tau: cos = (1 - tau^2) / (1 + tau^2), sin = 2 tau / (1 + tau^2), gamma = 2 arctan(tau)
    double x = first.x, d = 1.0 + x * x;
    double c1 = first_t ? (1.0 - x * x) / d : (x * x - 1.0) / d, s1 = 2.0 * x / d;
    double g1 = first_t ? 2.0 * std::atan(x) : M_PI - 2.0 * std::atan(x);
    x = second.x;
    d = 1.0 + x * x;
    double c2 = second_t ? (1.0 - x * x) / d : (x * x - 1.0) / d, s2 = -2.0 * x / d;
    double g2 = second_t ? 2.0 * M_PI - 2.0 * std::atan(x) : M_PI + 2.0 * std::atan(x);
    if (sigma > 0.0) return Arc{c1, s1, c2, s2, g2 - g1};  // around pi: from the first zero to the second
    return Arc{c2, s2, c1, s1, 2.0 * M_PI - (g2 - g1)};   // around 0: from the second to the first, + 2 pi
}

// LongBearing.components, eqs. (61)-(63): Sommerfeld's pressure, its positive part
void long_components(const Params& a, double clearance, double eps, double eps_dot, double omega_eff, double& f_n,
                     double& f_perp) {
    double s = std::sqrt(1.0 - eps * eps);
    double rho = eps * omega_eff * s / (2.0 + eps * eps);
    double sigma = eps_dot / (2.0 + 3.0 * eps * eps);
    Arc arc = long_arc(eps, rho, sigma);
    // g_n, g_t of film.py between the arc's ends, from their cosines and sines (no trigonometric calls)
    double d_cos = arc.c2 - arc.c1, d_sin = arc.s2 - arc.s1;
    double d_cos2 = (arc.c2 * arc.c2 - arc.s2 * arc.s2) - (arc.c1 * arc.c1 - arc.s1 * arc.s1);  // cos(2 x2) - cos(2 x1)
    double d_sin2 = 2.0 * (arc.s2 * arc.c2 - arc.s1 * arc.c1);                                  // sin(2 x2) - sin(2 x1)
    double two_eps_dot = 2.0 * eps_dot;
    // g_n: antiderivative of rho (2 cos + eps) sin + 2 eps_dot sin^2
    double in_n = rho * (-0.5 * d_cos2 - eps * d_cos) + two_eps_dot * (0.5 * arc.length - 0.25 * d_sin2);
    // g_t: antiderivative of (cos - eps) (rho (2 cos + eps) + 2 eps_dot sin)
    double in_t = (rho * (s * s * arc.length + 0.5 * d_sin2 - eps * d_sin)
                   + two_eps_dot * (-0.25 * d_cos2 + eps * d_cos));
    double scale = 6.0 * a.viscosity * a.r_j * a.r_j * a.r_j * a.length / (clearance * clearance);  // eq. (63)
    double s2_ = s * s;
    f_n = -scale * in_n / (s2_ * s);
    f_perp = scale * in_t / (s2_ * s2_);
}

// film.py _A1 ... _A9: Butenschoen's fits (1976), polynomials in B/D, lowest power first (eqs. (64)-(66))
const double FINITE_A[9][5] = {
    {1.1642, -1.9456, 7.1161, -10.1073, 5.0141},
    {-1.000026, -0.023634, -0.4215, -0.038817, -0.090551},
    {1.152624, -0.104565, 0.0, 0.0, 0.0},
    {-2.5905, 0.798745, 0.0, 0.0, 0.0},
    {8.73393, -2.3291, 0.0, 0.0, 0.0},
    {-13.3414, 3.424337, 0.0, 0.0, 0.0},
    {6.6294, -1.591732, 0.0, 0.0, 0.0},
    {0.70038, 3.2415, -12.2486, 18.895, -9.3561},
    {-0.999935, 0.0157434, -0.74224, 0.42278, -0.368928},
};
const int FINITE_A_DEGREE[9] = {4, 4, 1, 1, 1, 1, 1, 4, 4};
// film.py SQUEEZE_TURN: how fast a rotating film turns with the squeeze (eq. (66a))
const double SQUEEZE_TURN = 1.3;

double polynomial(const double* coefficients, int degree, double x) {  // film.py _polynomial
    double r = 0.0;
    for (int k = 0; k <= degree; ++k) r += coefficients[k] * std::pow(x, k);
    return r;
}

// FiniteBearing's a1 ... a9 at B/D = L / (2 R_J), kept per joint and recomputed when L or R_J change
// (FiniteBearing.__post_init__ computes them once per law)
struct FiniteCoefficients {
    double length = -1.0, r_j = -1.0, bd = 0.0;
    double c[9] = {};
};

const FiniteCoefficients& finite_coefficients(FiniteCoefficients& k, const Params& a) {
    if (k.length != a.length || k.r_j != a.r_j) {
        k.length = a.length;
        k.r_j = a.r_j;
        k.bd = a.length / (2.0 * a.r_j);
        for (int i = 0; i < 9; ++i) k.c[i] = polynomial(FINITE_A[i], FINITE_A_DEGREE[i], k.bd);
    }
    return k;
}

// FiniteBearing.squeeze, eq. (66): So_V at x = eps approaching the wall, x = -eps leaving it
double finite_squeeze(const FiniteCoefficients& k, double x) {
    const double* c = k.c;
    double bd = k.bd;
    double one_mx = 1.0 - x * x;
    double root_mx = std::sqrt(one_mx);
    return (4.0 * bd * bd / (one_mx * one_mx * root_mx)
            * ((0.5 * M_PI - 0.5 * std::acos(x)) * (1.0 + 2.0 * x * x) + 1.5 * x * root_mx)
            * c[7] * (1.0 - x) / (-c[8] - x));
}

// FiniteBearing.turning_squeeze, eq. (66a): the approaching and leaving numbers weighted by how far
// the squeeze has turned the rotating film; smooth in eps_dot wherever the film rotates
double finite_turning_squeeze(const FiniteCoefficients& k, double eps, double eps_dot, double omega_eff) {
    double wedge = eps * std::fabs(omega_eff) * std::sqrt(1.0 - eps * eps);
    double w = 0.5 + std::atan2(2.0 * SQUEEZE_TURN * eps_dot, wedge) / M_PI;  // atan2(0, 0) = 0: no force anyway
    if (w == 1.0) return finite_squeeze(k, eps);  // approaching without rotation, or far beyond the wedge
    if (w == 0.0) return finite_squeeze(k, -eps);
    return w * finite_squeeze(k, eps) + (1.0 - w) * finite_squeeze(k, -eps);
}

// FiniteBearing.components, eqs. (64)-(67): Butenschoen's rotation and squeeze fits
void finite_components(const Params& a, const FiniteCoefficients& k, double clearance, double eps, double eps_dot,
                       double omega_eff, double& f_n, double& f_perp) {
    const double* c = k.c;
    double bd = k.bd;
    // rotation, eqs. (64)-(65)
    double one_m = 1.0 - eps * eps;
    double so = (bd * bd * eps / (2.0 * one_m * one_m) * std::sqrt(M_PI * M_PI * one_m + 16.0 * eps * eps)
                 * c[0] * (eps - 1.0) / (c[1] + eps));
    double base = std::atan2(M_PI * std::sqrt(one_m), 2.0 * eps);
    double eps2 = eps * eps;
    double beta = base * (c[2] + c[3] * eps + c[4] * eps2 + c[5] * eps2 * eps + c[6] * eps2 * eps2);
    double so_v = finite_turning_squeeze(k, eps, eps_dot, omega_eff);
    double psi = clearance / a.r_j;
    double unit = a.length * 2.0 * a.r_j * a.viscosity / (psi * psi);  // B D eta / psi^2, eq. (67)
    double f_d = so * unit * std::fabs(omega_eff);
    double sgn = omega_eff >= 0.0 ? 1.0 : -1.0;
    double f_v = so_v * unit * eps_dot;  // signed: against the squeeze
    f_n = -f_d * std::cos(beta) - f_v;
    f_perp = sgn * f_d * std::sin(beta);
}

// FilmLaw.blended_load and _assemble: the film as the joint applies it (eqs. (68)-(70))
FilmLoad film_load(const Params& a, FiniteCoefficients& finite, const FilmInput& in) {
    double clearance = a.r_b - a.r_j;
    FilmKinematics kin = film_kinematics(in, clearance);
    double eps_b, eps_dot_b;
    blend_eccentricity(kin.eps, kin.eps_dot, a.eps_film, a.eps_cap, eps_b, eps_dot_b);
    double f_n = 0.0, f_perp = 0.0;
    if (a.film_model == FILM_SHORT) {
        short_components(a, clearance, eps_b, eps_dot_b, kin.omega_eff, f_n, f_perp);
    } else if (a.film_model == FILM_LONG) {
        long_components(a, clearance, eps_b, eps_dot_b, kin.omega_eff, f_n, f_perp);
    } else if (a.film_model == FILM_FINITE) {
        finite_components(a, finite_coefficients(finite, a), clearance, eps_b, eps_dot_b, kin.omega_eff, f_n, f_perp);
    } else {
        throw std::runtime_error("exuclear kernel: unknown film model " + std::to_string(a.film_model));
    }
    double fx = f_n * kin.nx - f_perp * kin.ny;  // n turned +90 degrees is (-n_y, n_x)
    double fy = f_n * kin.ny + f_perp * kin.nx;
    // eq. (69): Couette shear over the whole circumference, and the pressure's share
    double couette = (2.0 * M_PI * a.viscosity * a.r_j * a.r_j * a.r_j * a.length * (in.omega_journal - in.omega_bearing)
                      / (clearance * std::sqrt(1.0 - eps_b * eps_b)));
    double e_cross_f = kin.eps * clearance * (kin.nx * fy - kin.ny * fx);  // with the true e: no net moment
    return FilmLoad{fx, fy, -couette - 0.5 * e_cross_f, couette - 0.5 * e_cross_f};
}

// _python_kernel/film.py Film.add_loads: F = -F_film on the bearing, T = -M_J, the bearing's moment beyond T
void add_film_loads(double* loads, const FilmLoad& r) {
    loads[0] += -r.fx;
    loads[1] += -r.fy;
    loads[5] += -r.torque_journal;
    loads[8] += r.torque_bearing + r.torque_journal;
}

// Film.add_slice_loads: a spatial slice's share w / L of the film (section 10.8): -F on the bearing,
// T = s u x (-F) - M_J z, the bearing's moment beyond T (before p x F) e x F + (M_B + M_J) z
void add_film_slice_loads(double* loads, double share, const V3& u, const Kinematics& k, const FilmLoad& r) {
    double w = share;
    double fx = w * r.fx, fy = w * r.fy, m_j = w * r.torque_journal, m_b = w * r.torque_bearing;
    double sx = k.s * u[0], sy = k.s * u[1], sz = k.s * u[2];
    loads[0] += -fx;
    loads[1] += -fy;
    loads[3] += sz * fy;  // (s u) x (-F), F in the plane
    loads[4] += -sz * fx;
    loads[5] += -(sx * fy - sy * fx) - m_j;
    loads[8] += (k.ex * fy - k.ey * fx) + (m_b + m_j);
}

// _python_kernel/film.py slice_film_input: a slice's axis point, its rate in the bearing's rotating frame
// (the w of eq. (38)), the journal's spin relative to the bearing, the bearing's 0
FilmInput slice_film_input(const Kinematics& k, const V3& p, const V3& u, const V3& dv, const V3& dw, const V3& w_j) {
    V3 su{k.s * u[0], k.s * u[1], k.s * u[2]};
    double wx = dv[0] - (w_j[1] * p[2] - w_j[2] * p[1]) + (dw[1] * su[2] - dw[2] * su[1]);
    double wy = dv[1] - (w_j[2] * p[0] - w_j[0] * p[2]) + (dw[2] * su[0] - dw[0] * su[2]);
    return FilmInput{k.ex, k.ey, wx, wy, dw[0] * u[0] + dw[1] * u[1] + dw[2] * u[2], 0.0};
}

void set_film_outputs(History& h, const FilmLoad& r, double share) {  // Film.with_outputs
    h.film_fx = share * r.fx;
    h.film_fy = share * r.fy;
    h.film_torque = share * r.torque_journal;
}

double film_share(const Params& a) { return a.slices > 0 ? 1.0 / a.slices : 1.0; }  // w / L, eq. (41)

}  // namespace
