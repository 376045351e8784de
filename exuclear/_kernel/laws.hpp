// The contact laws (exuclear/contact/stiffness.py and law.py: stiffness models by kernel_code, the damped normal
// force of eq. (9)), the impact duration (exuclear/timescales.py) and the friction laws
// (exuclear/friction.py, eqs. (20)-(23)).  Python: exuclear/engine/_python_kernel/laws.py.

#pragma once

#include "kinematics.hpp"

namespace {

// ---- physics: contact.py -------------------------------------------------------------------
// Stiffness models by kernel_code; kp are their kernel_parameters() (exuclear/contact/stiffness.py).
const int STIFFNESS_CODES = 7;

// _LogLineContact._solve: s with s (ln(C/s) + beta) = delta, safeguarded Newton in (0, s_peak)
double log_line_solve(double delta, double c, double beta, double rtol, int max_iter) {
    double hi = c * std::exp(beta - 1.0);
    if (delta >= hi) return std::numeric_limits<double>::quiet_NaN();  // beyond the model's largest penetration
    double lo = 0.0;
    double s = delta / (std::log(c / delta) + beta);
    if (!(lo < s && s < hi)) s = 0.5 * hi;
    for (int i = 0; i < max_iter; ++i) {
        double log_term = std::log(c / s) + beta;
        double r = s * log_term - delta;
        if (r > 0.0) hi = s; else lo = s;
        double s_new = s - r / (log_term - 1.0);
        if (!(lo < s_new && s_new < hi)) s_new = 0.5 * (lo + hi);
        if (std::fabs(s_new - s) <= rtol * s_new) return s_new;
        s = s_new;
    }
    return s;
}

double elastic_force(const Params& a, double delta) {  // F_e(delta) for delta > 0
    const double* kp = a.kp;
    switch (a.stiffness_code) {
        case 0:  // hertz point contact: K delta^n
        case 6:  // pereira: K delta^n
            return kp[0] * std::pow(delta, kp[1]);
        case 1:  // liu, eq. (11): (pi E* L / 2) sqrt(1 / (2 (c + delta))) delta^n
            return kp[0] * std::sqrt(1.0 / (2.0 * (kp[1] + delta))) * std::pow(delta, kp[2]);
        case 2:  // johnson, radzimovsky, esdu-78035, dubowsky-freudenstein: implicit line contact
        case 3:
        case 4:
        case 5:
            return kp[0] * log_line_solve(delta, kp[1], kp[2], kp[3], static_cast<int>(kp[4]));
        default:
            throw std::runtime_error("exuclear kernel: unknown stiffness code " + std::to_string(a.stiffness_code));
    }
}

// ---- physics: timescales.py ---------------------------------------------------------------
// Gauss-Legendre nodes and weights on [0, 1] (timescales.py _GAUSS_NODES, _GAUSS_WEIGHTS), in w
// with delta = delta_max w^2; and the relative tolerance of the impact's depth (_DEPTH_RTOL).
const double GAUSS_NODES[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
const double GAUSS_WEIGHTS[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};
const double DEPTH_RTOL = 1e-6;
const int DEPTH_MAX_ITER = 200;  // timescales.py PENETRATION_MAX_ITER

double stored_energy(const Params& a, double delta) {  // timescales.py stored_energy: int_0^delta F_e
    double total = 0.0;
    for (int i = 0; i < 4; ++i) {
        double w = GAUSS_NODES[i];
        total += GAUSS_WEIGHTS[i] * 2.0 * w * elastic_force(a, delta * w * w);
    }
    return delta * total;
}

// Where a function rising on (0, hi] reaches `target`: bisection to rtol of the bracket, a NaN
// (beyond a line-contact law's largest penetration) counting as above any target
// (timescales.py penetration_at and impact_duration)
template <typename F> double bisect_rising(F value, double target, double hi, double rtol, int max_iter) {
    double lo = 0.0;
    for (int i = 0; i < max_iter; ++i) {
        double mid = 0.5 * (lo + hi);
        double v = value(mid);
        if (std::isnan(v) || v >= target) hi = mid; else lo = mid;
        if (hi - lo <= rtol * hi) break;
    }
    return 0.5 * (lo + hi);
}

// timescales.py impact_duration: pi delta_max / |v|, delta_max where the stored energy equals
// m v^2 / 2 (c beyond the clearance); the caller passes a positive, finite mass and a speed != 0
double impact_duration(const Params& a, double mass, double speed) {
    double energy = 0.5 * mass * speed * speed;
    double hi = a.r_b - a.r_j;
    double depth;
    if (!(stored_energy(a, hi) > energy)) {  // NaN (beyond a line-contact law's range) counts as above
        depth = hi;
    } else {
        depth = bisect_rising([&](double x) { return stored_energy(a, x); }, energy, hi, DEPTH_RTOL, DEPTH_MAX_ITER);
    }
    return M_PI * depth / std::fabs(speed);
}

// contact.py damped_normal_force, eq. (9) for delta > 0: the elastic force f_e with the
// hysteresis factor D and the onset velocity floored at v_min
double damped_normal_force(double f_e, double damping_factor, double v_min, double delta_dot, double v0) {
    double v0_eff = v0 > v_min ? v0 : v_min;
    double f = f_e * (1.0 + damping_factor * delta_dot / v0_eff);
    return f < 0.0 ? 0.0 : f;  // no adhesion; a NaN stays NaN, to be caught
}

// ---- physics: friction.py ------------------------------------------------------------------
double smooth_step(double x, double x0, double h0, double x1, double h1) {  // S(x; x0, h0, x1, h1)
    double s = (x - x0) / (x1 - x0);
    s = s < 0.0 ? 0.0 : s;  // max(s, 0), as Python's max returns the first of equals
    s = 1.0 < s ? 1.0 : s;  // min(s, 1)
    return h0 + (h1 - h0) * s * s * (3.0 - 2.0 * s);
}

double sign(double x) { return x > 0.0 ? 1.0 : (x < 0.0 ? -1.0 : 0.0); }

double friction_coefficient(const Params& a, double v_t) {  // mu(v_T), eqs. (20)-(23)
    switch (a.friction_code) {
        case FRICTION_COULOMB: {  // fp = (mu, v_eps)
            double mu = a.fp[0], v_eps = a.fp[1];
            return sign(v_t) * smooth_step(std::fabs(v_t), -v_eps, -mu, v_eps, mu);
        }
        case FRICTION_MODIFIED_COULOMB: {  // fp = (mu_s, mu_d, v_s, v_d)
            double mu_s = a.fp[0], mu_d = a.fp[1], v_s = a.fp[2], v_d = a.fp[3];
            double speed = std::fabs(v_t);
            double mu = speed < v_s   ? smooth_step(speed, -v_s, -mu_s, v_s, mu_s)
                        : speed < v_d ? smooth_step(speed, v_s, mu_s, v_d, mu_d)
                                      : mu_d;
            return sign(v_t) * mu;
        }
        default:
            return 0.0;
    }
}

}  // namespace
