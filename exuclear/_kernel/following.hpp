// The contact-following mode on the compiled kernel (contact_mode="follow", issue 34): a planar,
// dry, unworn joint between 2D rigid bodies, 3D rigid bodies with Euler parameters, or the
// ground.  Python:
// exuclear/engine/_python_kernel/following.py FollowState (the per-step decisions, whose rules
// and constants these mirror) and exuclear/engine/follow_conditions.py (the condition).
//
// What differs from the Python kernel's mode, and why:
// - The condition's rows n^T dv/dq_t are taken at Newton's first iterate of each step, with the
//   end acceleration that iterate leaves out extrapolated from the accepted velocities (the
//   condition's own constraint and Jacobian functions, which Exudyn calls without Python), not
//   at the configuration the Python kernel predicts from the integrator's state (which would
//   need the whole system's coordinates from Python at every step).
// - Friction acts in the condition's reaction (condition_jacobian), from Newton's present
//   multiplier and slip, not from the mean of that multiplier and the last accepted one, which
//   no compiled function can read.
// - Python is called at events only (a switch, a run start, Newton's tolerance where it moves
//   by more than TOLERANCE_MOVE), and once per followed step for the condition's multiplier.

#pragma once

#include <pybind11/numpy.h>

#include <map>
#include <utility>

#include "step_control.hpp"

namespace {

// ---- the rules: _python_kernel/following.py and follow_conditions.py (a test keeps them equal) ----
const double FOLLOW_PERIODS = 5.0;
const double FOLLOW_STEP = 0.5;
const double FOLLOW_TURN = 0.1;
const double FOLLOW_HOLD = 1.0;
const double FOLLOW_HOLD_FRICTION = 0.5;
const int HOLD_REDOS = 3;
const int FOLLOW_MIN_STEPS = 3;
const double FOLLOW_RATE = 0.1;
const double FOLLOW_GAIN = 0.25;
const double GA_BETA = 0.25;
const double FOLLOW_DEAD_BAND = 5e-3;
const double FOLLOW_FILTER = 0.2;
const double FOLLOW_ATOL_SHARE = 1e-4;
const double FOLLOW_ATOL_FORCE = 1e-13;
const double DAMPED_RTOL = 1e-12;
const int DAMPED_MAX_ITER = 200;
const double DAMPED_FIRST = 1e-3;
const double END_SLACK = 1e-12;
const double STICK_MARGIN = 10.0;
const double RATE_GAIN = 0.5;          // follow_conditions.py
const double PENETRATION_RTOL = 1e-12;  // timescales.py
const int PENETRATION_MAX_ITER = 200;
const double STIFFNESS_EPS = 1e-6;
// Newton's absolute tolerance (FOLLOW_ATOL_SHARE) is passed to Python where it moves by more
// than this share since it was last set, not at every step as the Python kernel does.
const double TOLERANCE_MOVE = 0.05;

// ---- physics: timescales.py penetration_at, contact_stiffness, contact_period -------------
double penetration_at(const Params& a, double force) {
    double hi = a.r_b - a.r_j;
    if (elastic_force(a, hi) <= force) return hi;
    return bisect_rising([&](double x) { return elastic_force(a, x); }, force, hi, PENETRATION_RTOL,
                         PENETRATION_MAX_ITER);
}

double contact_stiffness(const Params& a, double delta) {
    double h = STIFFNESS_EPS * delta;
    return (elastic_force(a, delta + h) - elastic_force(a, delta - h)) / (2.0 * h);
}

double contact_period(const Params& a, double mass, double force) {
    return 2.0 * M_PI * std::sqrt(mass / contact_stiffness(a, penetration_at(a, force)));
}

// One side of the condition (SideKind, kinematics.hpp): the marker at `local` in the body (the
// ground: global), and its frame's z axis there (side 0 only: the bearing's axis).
struct ConditionSide {
    int kind = SIDE_GROUND;
    V3 local{0.0, 0.0, 0.0};
    V3 axis{0.0, 0.0, 1.0};
    // side 0: the joint frame J0 in the body (the marker's frame turned by the connector's
    // rotationMarker0), whose z column is `axis`
    M3 frame{V3{1.0, 0.0, 0.0}, V3{0.0, 1.0, 0.0}, V3{0.0, 0.0, 1.0}};
};

// FollowState: one joint's following mode.
struct Follow {
    int item = -1;  // the condition's object number
    ConditionSide sides[2];
    py::object events;  // Python: exuclear.engine.following.CompiledEvents
    // the state of _python_kernel/following.py FollowState.reset
    bool active = false;
    double multiplier = 0.0, raw = 0.0, filtered = 0.0;
    long steps_in_contact = 0;
    long on_count = 0, off_count = 0, redone = 0, lost = 0, followed_steps = 0;
    bool barred = false, damping_checked = false, undamped = false;
    double end_time = INF;  // the run's end time, read with the damping
    bool parked = false;    // the condition switched off at the run's last step, holding the contact
    double hold_start = -INF;
    int hold_redos = 0;
    double distance = 0.0;
    double tolerance = 0.0;  // the last absolute tolerance passed to Python (0: none)
    // the condition: the step's start, |e| there, the rows for the step ending at rows_time
    double start = 0.0, norm = 0.0, rows_time = -INF;
    double before_start = NAN, before_norm = 0.0;  // the last start's, for a step another joint redoes
    std::vector<double> rows;
    // with friction: the rows t^T dv_c/dq_t of the contact points' slip, and the joint's parameters
    std::vector<double> slip_rows;
    Params params{};
    std::vector<double> row_coordinates;  // the coordinates the rows are taken at (storage reused)
    // the bodies' coordinates and velocities at the condition's last evaluation (Newton's last
    // iterate: Exudyn evaluates the residual at each iterate and stops at one that converged),
    // and their velocities at the last three accepted followed steps (accepted_count of them)
    double last_time = NAN;
    std::vector<double> last_q, last_v;
    // the carrier's post-Newton call in the sweep in which the joint's own switched the
    // condition on (at carrier_skip_time) has nothing to do: that step is the joint's
    double carrier_skip_time = NAN;
    py::array_t<double> jacobian;  // the condition's Jacobian, returned to Exudyn (condition_jacobian)
    double accepted_time[3] = {0.0, 0.0, 0.0};
    std::vector<double> accepted_v[3];
    int accepted_count = 0;
    // Exudyn's first iterate of a step takes the end acceleration as 0; its share in the end's
    // position is guess_share h^2 a_1 (generalized-alpha: beta (1 - alpha_f) / (1 - alpha_m))
    double guess_share = 0.0;
};

std::map<long, Follow> g_follow;  // by joint id
std::map<std::pair<const void*, int>, long> g_conditions;  // (system, condition's item) -> joint id

Follow* follow_of(long id) {
    auto it = g_follow.find(id);
    return it == g_follow.end() ? nullptr : &it->second;
}

void forget_follow(long id) {
    g_follow.erase(id);
    for (auto it = g_conditions.begin(); it != g_conditions.end();) {
        it = it->second == id ? g_conditions.erase(it) : std::next(it);
    }
}

// A call into the joint's Python events object; an exception there stops the run, as it
// would in the Python kernel.
template <typename... Args> py::object tell(Follow& f, const char* what, Args... args) {
    return f.events.attr(what)(args...);
}

// FollowState.reset and restart: a new run begins, compliant, the condition off
void follow_restart(Follow& f) {
    if (!f.events.is_none()) tell(f, "restart");
    Follow fresh;
    fresh.item = f.item;
    fresh.sides[0] = f.sides[0];
    fresh.sides[1] = f.sides[1];
    fresh.events = f.events;
    f = fresh;
}

// FollowState.damped_penetration: the penetration x where the law's force, elastic and
// damping at the rate (x - delta) / h, is `force` (secant inside a narrowing bracket on (0, c])
double damped_penetration(const Params& a, double force, double delta, double h, double v0) {
    auto excess = [&](double x) {
        double f = damped_normal_force(elastic_force(a, x), a.damping_factor, a.v_min, (x - delta) / h, v0);
        return std::isnan(f) ? INF : f - force;
    };
    double lo = 0.0, hi = a.r_b - a.r_j;
    double x = std::min(std::max(delta, DAMPED_RTOL * hi), hi);
    double x0 = NAN, g0 = NAN;
    for (int i = 0; i < DAMPED_MAX_ITER; ++i) {
        double g = excess(x);
        if (g >= 0.0) hi = x; else lo = x;
        if (hi - lo <= DAMPED_RTOL * hi) break;
        double step;
        if (std::isnan(x0)) {
            step = x * (g >= 0.0 ? -DAMPED_FIRST : DAMPED_FIRST);
        } else if (std::isfinite(g) && std::isfinite(g0) && g != g0) {
            step = -g * (x - x0) / (g - g0);
        } else {
            step = NAN;
        }
        x0 = x;
        g0 = g;
        if (std::isfinite(step) && std::fabs(step) <= DAMPED_RTOL * x) return x + step;
        x = (lo < x + step && x + step < hi) ? x + step : 0.5 * (lo + hi);
    }
    return 0.5 * (lo + hi);
}

// friction.py smoothing_speed: the half-width of the band where mu is the smoothed sign
double smoothing_speed(const Params& a) {
    switch (a.friction_code) {
        case FRICTION_COULOMB: return a.fp[1];            // v_eps
        case FRICTION_MODIFIED_COULOMB: return a.fp[2];   // v_s
        default: return 0.0;
    }
}

// FollowState.sticking: the slip within STICK_MARGIN times the friction law's smoothing band
bool sticking(const Params& a, double slip) {
    return a.friction_code != FRICTION_NONE && std::fabs(slip) < STICK_MARGIN * smoothing_speed(a);
}

bool follow_holds(const Follow& f, const Params& a, double delta) {  // FollowState.holds
    double held = f.distance - (a.r_b - a.r_j);
    double share = a.friction_code != FRICTION_NONE ? FOLLOW_HOLD_FRICTION : FOLLOW_HOLD;
    return std::fabs(delta - held) <= share * held;
}

// FollowState.hold_step: the shorter step to redo a followed step with, 0 to accept it
double follow_hold_step(Follow& f, const Params& a, double delta, double h, double start, const StepControl& c) {
    if (follow_holds(f, a, delta) || !c.can_shorten || 0.5 * h < c.min_step) return 0.0;
    if (start != f.hold_start) {
        f.hold_start = start;
        f.hold_redos = 0;
    }
    if (f.hold_redos >= HOLD_REDOS) return 0.0;
    f.hold_redos++;
    f.redone++;
    return 0.5 * h;
}

// JointStepControl.held_cap: a followed step longer than the run's contact_cap is redone at it
double held_cap(const StepControl& c, double h, double impact_step) {
    if (c.can_shorten && c.rate && !(impact_step > 0.0) && h > c.contact_cap * (1.0 + STEP_SLACK)) return c.contact_cap;
    return 0.0;
}

// The condition holds for the step after the accepted state at t, |e| = norm there; keeps the
// bodies' state at t where the condition's last evaluation was at t (a followed step)
void follow_hold(Follow& f, double t, double norm) {
    f.before_start = f.active ? f.start : NAN;
    f.before_norm = f.norm;
    f.start = t;
    f.norm = norm;
    f.rows_time = -INF;
    if (f.last_time != t) {
        f.accepted_count = 0;
        return;
    }
    while (f.accepted_count > 0 && f.accepted_time[f.accepted_count - 1] >= t) {
        f.accepted_count--;  // a step accepted, then redone for another joint: its state is gone
    }
    if (f.accepted_count == 3) {
        for (int i = 0; i < 2; ++i) {
            std::swap(f.accepted_v[i], f.accepted_v[i + 1]);
            f.accepted_time[i] = f.accepted_time[i + 1];
        }
        f.accepted_count = 2;
    }
    int i = f.accepted_count++;
    f.accepted_time[i] = t;
    f.accepted_v[i] = f.last_v;
}

void follow_tolerance(Follow& f, double delta, double force) {  // FollowState._tolerance, where it moved
    double wanted = std::max(FOLLOW_ATOL_SHARE * delta, FOLLOW_ATOL_FORCE * force);
    if (f.tolerance > 0.0 && std::fabs(wanted - f.tolerance) <= TOLERANCE_MOVE * f.tolerance) return;
    f.tolerance = wanted;
    tell(f, "tolerance", delta, force);
}

void follow_release(Follow& f) {  // FollowState._release
    tell(f, "switch", false);
    f.active = false;
    f.tolerance = 0.0;
    f.off_count++;
    f.multiplier = f.raw = 0.0;
    f.steps_in_contact = 0;
}

// FollowState._track: the distance towards c + delta(lambda), outside the dead band
void follow_track(Follow& f, const Params& a, double h, double lam, double mean, double mass, double v0) {
    f.filtered += FOLLOW_FILTER * (lam - f.filtered);
    double clearance = a.r_b - a.r_j;
    if (!(mass > 0.0 && std::isfinite(mass) && h > 0.0 && mean > 0.0)) return;
    double delta_lam = damped_penetration(a, mean, f.distance - clearance, h, v0);
    double off = clearance + delta_lam - f.distance;
    if (std::fabs(off) <= FOLLOW_DEAD_BAND * delta_lam) return;
    double k = contact_stiffness(a, delta_lam);
    double omega = std::min(1.0, FOLLOW_GAIN * GA_BETA * h * h * k / mass);
    f.distance += omega * off;
}

// FollowState._decide: an accepted step of length h ending at t (the contact's state `now`,
// `before` at the step's start): release, update delta(lambda), or switch on.
void follow_decide(Follow& f, const Params& a, const StepControl& c, const void* system, double t, double h,
                   const History& before, const History& now) {
    double clearance = a.r_b - a.r_j;
    double mass = c.impact_mass;
    if (f.active) {
        double raw = tell(f, "multiplier").cast<double>();
        double mean = 0.5 * (raw + f.raw);
        double lam = raw;
        f.raw = raw;
        double filtered = f.filtered + FOLLOW_FILTER * (lam - f.filtered);
        if (filtered <= 0.0 || sticking(a, now.v_t)) {  // RELEASE_FILTERED; sticking: |e| = d, the compliant force lambda
            follow_release(f);
            return;
        }
        if (!follow_holds(f, a, now.delta)) {  // the condition no longer holds |e| = d
            f.lost++;
            f.barred = true;
            follow_release(f);
            return;
        }
        f.multiplier = lam;
        f.followed_steps++;
        follow_track(f, a, h, lam, mean, mass, now.v0);
        follow_hold(f, t, clearance + now.delta);
        follow_tolerance(f, f.distance - clearance, lam);
        return;
    }
    f.steps_in_contact = now.in_contact && now.delta > 0.0 ? f.steps_in_contact + 1 : 0;
    if (f.steps_in_contact == 0) f.barred = false;
    if (f.barred) return;
    if (f.steps_in_contact < FOLLOW_MIN_STEPS || !(now.f_n > 0.0)) return;
    if (!f.damping_checked) {
        f.damping_checked = true;
        f.undamped = !tell(f, "damped").cast<bool>();
        f.guess_share = tell(f, "guess_share").cast<double>();
        f.end_time = tell(f, "end_time").cast<double>();
    }
    if (f.undamped) return;
    double turn = std::atan2(before.ex * now.ey - before.ey * now.ex, before.ex * now.ex + before.ey * now.ey);
    if (std::fabs(now.delta_dot) > FOLLOW_RATE * a.v_min || std::fabs(turn) > FOLLOW_TURN || sticking(a, now.v_t)) return;
    if (mass > 0.0 && std::isfinite(mass)) {
        double period = contact_period(a, mass, now.f_n);
        if (t - now.onset_time < FOLLOW_PERIODS * period || h < FOLLOW_STEP * period) return;
    }
    // consistent: the distance is the present |e|, the rate is small
    f.distance = clearance + now.delta;
    f.params = a;
    follow_hold(f, t, f.distance);
    g_conditions[{system, f.item}] = a.id;
    tell(f, "switch", true);
    f.active = true;
    f.carrier_skip_time = t;  // the carrier, on from now, is called next in this sweep
    f.tolerance = 0.0;
    follow_tolerance(f, now.delta, now.f_n);
    f.multiplier = f.raw = f.filtered = now.f_n;
    f.on_count++;
}

// FollowState.after_step: the decisions, then the condition parked at the run's last step where it
// holds the contact (FollowState._park: a run started again on the same system finds it off)
void follow_after_step(Follow& f, const Params& a, const StepControl& c, const void* system, double t, double h,
                       const History& before, const History& now) {
    if (f.parked) {  // the run's last step redone for another joint after the park: compliant since
        f.parked = false;
        f.off_count++;
    }
    follow_decide(f, a, c, system, t, h, before, now);
    if (f.active && t >= f.end_time - END_SLACK * std::max(1.0, std::fabs(f.end_time))) {
        tell(f, "switch", false);
        f.active = false;
        f.tolerance = 0.0;
        f.parked = true;
    }
}

// ---- the condition's functions (ObjectConnectorCoordinateVector, velocityLevel) ----------
// follow_conditions.py VelocityCondition: n . (v_journal - v_bearing) = r, r = RATE_GAIN (d - |e_0|) / h,
// in rows n^T dv/dq_t taken at Newton's first iterate of the step (the first call at a new t).
Follow* condition_of(const MainSystem& mbs, int item) {
    auto it = g_conditions.find({&mbs, item});
    return it == g_conditions.end() ? nullptr : follow_of(it->second);
}

// The coordinates at the step's end t: Newton's first iterate `q`, whose end acceleration
// (taken as 0 there) is extrapolated from the mean accelerations of the last two accepted
// followed steps ((v_1 - v_0) / h at their middles; the last one's where only one is known).  A
// rotation vector's velocity coordinates are the body-fixed angular velocity, not its rate: its
// share is added to the vector as if the tangent map were the identity, an error of order
// |v| guess_share h^2 alpha in a correction of order 1e-3 h^2 alpha
const std::vector<double>& predicted(Follow& f, double t, const std::vector<double>& q, std::vector<double>& out) {
    int n = f.accepted_count;
    if (n < 2 || f.guess_share == 0.0 || f.accepted_v[0].size() != q.size()) return q;
    const double* tt = f.accepted_time;
    double h = t - tt[n - 1];
    double t_b = 0.5 * (tt[n - 2] + tt[n - 1]), t_a = n == 3 ? 0.5 * (tt[0] + tt[1]) : t_b;
    out.resize(q.size());
    for (size_t i = 0; i < q.size(); ++i) {
        double a_b = (f.accepted_v[n - 1][i] - f.accepted_v[n - 2][i]) / (tt[n - 1] - tt[n - 2]);
        double a_end = a_b;
        if (n == 3) {
            double a_a = (f.accepted_v[1][i] - f.accepted_v[0][i]) / (tt[1] - tt[0]);
            a_end = a_b + (t - t_b) * (a_b - a_a) / (t_b - t_a);
        }
        out[i] = q[i] + f.guess_share * h * h * a_end;
    }
    return out;
}


// A moving side's pose at its coordinates q: its rotation (returned; a 3D body: W of omega = W q_t),
// the marker's lever r = A local from the node and its position p
M3 side_pose(const ConditionSide& s, const double* q, double w[3][4], V3& r, V3& p) {
    M3 a = side_rotation(s.kind, q, w);
    r = turn(a, s.local);
    double z = s.kind == SIDE_RIGID_2D ? 0.0 : q[2];
    p = V3{q[0] + r[0], q[1] + r[1], z + r[2]};
    return a;
}

// The rows d^T dv/dq_t of both sides for the direction d, at the points `lever` from the bodies'
// nodes: v = x_t + omega x lever, so d . v = d . x_t + (lever x d) . omega; side 0 with the sign
// of Exudyn's X_1 q_1 - X_0 q_0
void add_rows(std::vector<double>& rows, const ConditionSide* sides, const V3* lever, const double w[2][3][4],
              const V3& d) {
    rows.clear();
    for (int k = 0; k < 2; ++k) {
        int kind = sides[k].kind;
        if (kind == SIDE_GROUND) continue;
        double sign = k == 0 ? -1.0 : 1.0;
        V3 ld = cross(lever[k], d);
        rows.push_back(sign * d[0]);
        rows.push_back(sign * d[1]);
        if (kind == SIDE_RIGID_2D) {  // omega = phi_t e_z
            rows.push_back(sign * ld[2]);
            continue;
        }
        rows.push_back(sign * d[2]);
        for (int j = 0; j < SIDE_COORDINATES[kind] - 3; ++j) {  // omega = W q_t
            rows.push_back(sign * (ld[0] * w[k][0][j] + ld[1] * w[k][1][j] + ld[2] * w[k][2][j]));
        }
    }
}

// The rows n^T dv/dq_t of both sides at the coordinates predicted for the step's end t, n the
// unit eccentricity in the bearing's plane: v = x_t + omega x r, so n . v = n . x_t + (r x n) . omega
void condition_rows(Follow& f, double t, const std::vector<double>& first_iterate) {
    if (t == f.rows_time) return;
    const std::vector<double>& q = predicted(f, t, first_iterate, f.row_coordinates);
    V3 p[2], r[2], axis{0.0, 0.0, 1.0};
    double g[2][3][4] = {};
    size_t at = 0;
    for (int k = 0; k < 2; ++k) {
        const ConditionSide& s = f.sides[k];
        if (s.kind == SIDE_GROUND) {
            r[k] = V3{0.0, 0.0, 0.0};
            p[k] = s.local;
            if (k == 0) axis = s.axis;
            continue;
        }
        M3 a = side_pose(s, &q[at], g[k], r[k], p[k]);
        if (k == 0) axis = turn(a, s.axis);
        at += static_cast<size_t>(SIDE_COORDINATES[s.kind]);
    }
    V3 e{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    double along = dot(e, axis);
    e = V3{e[0] - along * axis[0], e[1] - along * axis[1], e[2] - along * axis[2]};
    double norm = std::sqrt(dot(e, e));
    V3 n = norm > 0.0 ? V3{e[0] / norm, e[1] / norm, e[2] / norm} : V3{1.0, 0.0, 0.0};
    add_rows(f.rows, f.sides, r, g, n);
    if (f.params.friction_code != FRICTION_NONE) {
        // the slip t . (v_Jc - v_Bc) of the contact points, at R_J n and R_B n from the centres
        // (eq. (8): t . dv - omega_i R_J + omega_j R_B), t = n x axis
        V3 tangent = cross(n, axis);
        V3 lever[2];
        for (int k = 0; k < 2; ++k) {
            double radius = k == 0 ? f.params.r_b : f.params.r_j;
            lever[k] = V3{r[k][0] + radius * n[0], r[k][1] + radius * n[1], r[k][2] + radius * n[2]};
        }
        add_rows(f.slip_rows, f.sides, lever, g, tangent);
    }
    f.rows_time = t;
}

std::vector<double> condition_constraint(const MainSystem& mbs, double t, int item, std::vector<double> q,
                                         std::vector<double> q_t, bool) {
    Follow* f = condition_of(mbs, item);
    if (f == nullptr) return {0.0};  // not switched on in this system yet: Exudyn evaluates it inactive
    if (t < f->start && !std::isnan(f->before_start)) {
        // the step that ended at the start is redone (another joint asked for it after this one
        // accepted it): back to that step's start (VelocityCondition.fit)
        f->start = f->before_start;
        f->norm = f->before_norm;
        f->before_start = NAN;
    }
    condition_rows(*f, t, q);
    double h = t - f->start;
    double rate = h > 0.0 ? RATE_GAIN * (f->distance - f->norm) / h : 0.0;
    double c = -rate;
    for (size_t i = 0; i < f->rows.size() && i < q_t.size(); ++i) c += f->rows[i] * q_t[i];
    f->last_time = t;
    f->last_q.swap(q);  // Exudyn's copies, kept without another copy
    f->last_v.swap(q_t);
    return {c};
}

// The joint's relative motion in its frame J0 at the condition's last evaluation (Newton's last
// iterate at t), as Exudyn gives it to the joint's connector (ObjectConnectorRigidBodySpringDamper's
// DisplacementLocal, VelocityLocal and AngularVelocityLocal: (A_0 R_0)^T (x_1 - x_0) of the
// markers' positions, velocities v = x_t + omega x r and angular velocities): the joint's
// post-Newton input while its connector is off and the carrier calls it (bindings.cpp).  False
// where the condition was not evaluated at t.
bool carried_motion(const Follow& f, double t, V3& displacement, V3& velocity, V3& angular) {
    if (f.last_time != t) return false;
    const std::vector<double>& q = f.last_q;
    const std::vector<double>& q_t = f.last_v;
    V3 p[2], v[2], w[2];
    M3 j0 = f.sides[0].frame;
    size_t at = 0;
    for (int k = 0; k < 2; ++k) {
        const ConditionSide& s = f.sides[k];
        v[k] = w[k] = V3{0.0, 0.0, 0.0};
        if (s.kind == SIDE_GROUND) {
            p[k] = s.local;
            continue;
        }
        size_t n = static_cast<size_t>(SIDE_COORDINATES[s.kind]);
        if (at + n > q.size() || at + n > q_t.size()) return false;
        double g[3][4] = {};
        V3 r;
        M3 a = side_pose(s, &q[at], g, r, p[k]);
        const double* x_t = &q_t[at];
        V3 centre_v{x_t[0], x_t[1], 0.0};
        if (s.kind == SIDE_RIGID_2D) {  // omega = phi_t e_z
            w[k] = V3{0.0, 0.0, x_t[2]};
        } else {  // omega = W q_t
            centre_v[2] = x_t[2];
            for (int i = 0; i < 3; ++i) {
                for (int j = 0; j < SIDE_COORDINATES[s.kind] - 3; ++j) w[k][i] += g[i][j] * x_t[3 + j];
            }
        }
        V3 spin = cross(w[k], r);
        v[k] = V3{centre_v[0] + spin[0], centre_v[1] + spin[1], centre_v[2] + spin[2]};
        if (k == 0) {  // J0 = A_0 R_0
            for (int i = 0; i < 3; ++i) {
                for (int j = 0; j < 3; ++j) {
                    j0[i][j] = a[i][0] * s.frame[0][j] + a[i][1] * s.frame[1][j] + a[i][2] * s.frame[2][j];
                }
            }
        }
        at += n;
    }
    for (int i = 0; i < 3; ++i) {  // (J0)^T (x_1 - x_0)
        displacement[i] = velocity[i] = angular[i] = 0.0;
        for (int j = 0; j < 3; ++j) {
            displacement[i] += j0[j][i] * (p[1][j] - p[0][j]);
            velocity[i] += j0[j][i] * (v[1][j] - v[0][j]);
            angular[i] += j0[j][i] * (w[1][j] - w[0][j]);
        }
    }
    return true;
}

// The condition's Jacobian, which Exudyn also takes for the reaction J^T lambda at every residual:
// with friction the rows n^T dv/dq_t + mu(v_t) t^T dv_c/dq_t, so that the reaction is the normal
// force lambda and the friction force mu(v_t) lambda at the contact points, from Newton's present
// multiplier and slip (eqs. (20)-(24)); the constraint itself stays n . v = r.
py::object condition_jacobian(const MainSystem& mbs, double t, int item, std::vector<double> q, std::vector<double> q_t,
                              bool) {
    Follow* f = condition_of(mbs, item);
    // one array per condition, filled again at each call (Exudyn copies it into its own matrix):
    // a new NumPy array per call cost about 1 us, at every residual
    py::array_t<double> fresh;  // a condition not switched on in this system yet
    py::array_t<double>& jac = f != nullptr ? f->jacobian : fresh;
    if (jac.ndim() != 2 || jac.shape(1) != static_cast<py::ssize_t>(q.size())) {
        jac = py::array_t<double>({static_cast<py::ssize_t>(1), static_cast<py::ssize_t>(q.size())});
    }
    auto m = jac.mutable_unchecked<2>();
    for (py::ssize_t i = 0; i < static_cast<py::ssize_t>(q.size()); ++i) m(0, i) = 0.0;
    if (f != nullptr) {
        condition_rows(*f, t, q);
        double mu = 0.0;
        if (f->params.friction_code != FRICTION_NONE && f->slip_rows.size() == f->rows.size()) {
            double slip = 0.0;
            for (size_t i = 0; i < f->slip_rows.size() && i < q_t.size(); ++i) slip += f->slip_rows[i] * q_t[i];
            mu = friction_coefficient(f->params, slip);
        }
        for (size_t i = 0; i < f->rows.size() && i < q.size(); ++i) {
            m(0, static_cast<py::ssize_t>(i)) = f->rows[i] + (mu != 0.0 ? mu * f->slip_rows[i] : 0.0);
        }
    }
    return jac;
}

}  // namespace
