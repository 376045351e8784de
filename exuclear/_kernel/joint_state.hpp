// One joint's state in the kernel's table (JointState, by the joint id in its parameters): per
// contact, the history at the start and the end of the last accepted step, which of them an
// evaluation uses (history_for), the joint's kinematics and its force evaluation, and the
// data node's entries of a history, and a planar joint's wear (which profiles an evaluation
// uses, the wear of an accepted step).  Python: exuclear/engine/_python_kernel/joint_state.py.

#pragma once

#include <unordered_map>

#include "film.hpp"
#include "wear.hpp"

namespace {

// ---- the per-joint table -------------------------------------------------------------------
// One joint's state (_python_kernel/joint_state.py JointState): per contact, its history at the start
// (prev) and at the end (cur) of the last post-processed step and its records.
// What the joint's own step control holds through a run: layout.py STEP_CONTROL, the one table
// of its fields (name, default, meaning), in its order; a test keeps this copy equal to it.
// RUN_START_FIELDS are set from the run-start callback's record (layout.py RunStart, read by
// name in start_run); STEP_COUNT_FIELDS are what the run did (read by the handle after the
// run, which says in an AccuracyWarning what the joint could not resolve).  Each entry:
// X(type, name, default); TOLD_FIELDS is layout.py's _told: a kind of step accepted although
// a rule asked for a shorter one, its count and the end and length of the first.
#define RUN_START_FIELDS(X)                                                                         \
    X(bool, can_shorten, true) X(double, min_step, 0.0) X(std::string, label, "") X(bool, rate, true) \
    X(int, group_size, 1) X(double, rate_scale, 1.0)                                                \
    X(double, growth_cap, INF) X(double, contact_cap, INF) X(double, jacobian_step, INF)            \
    X(double, separation_step, INF) X(double, impact_mass, std::numeric_limits<double>::quiet_NaN()) \
    X(std::string, refusal, "") X(double, end_time, INF)
#define TOLD_FIELDS(X, count, first) X(long, count, 0) X(double, first##_time, 0.0) X(double, first##_step, 0.0)
#define STEP_COUNT_FIELDS(X)                                                                        \
    X(long, runs, 0) X(bool, jacobian_on, false)                                                    \
    X(long, separations, 0) X(long, long_separations, 0) X(long, last_ended, 0) X(long, last_long, 0) \
    X(long, rejected, 0)                                                                            \
    TOLD_FIELDS(X, unresolved, unresolved) X(double, unresolved_advice, INF)                        \
    TOLD_FIELDS(X, held_long, held)                                                                 \
    TOLD_FIELDS(X, over_limit, over) X(double, deepest, 0.0)                                        \
    X(double, last_time, -INF) X(double, last_step, 0.0) X(double, retry_start, -INF) X(int, retries, 0)  \
    X(bool, finished, false)
#define DECLARE_FIELD(type, name, value) type name = value;
struct StepControl {
    RUN_START_FIELDS(DECLARE_FIELD)
    STEP_COUNT_FIELDS(DECLARE_FIELD)
};
#undef DECLARE_FIELD

struct JointState {
    bool in_use = true;    // false: released (its handle is gone), the slot is free for a new joint
    bool started = false;  // an accepted (initial) state exists in this run
    std::vector<Kinematics> kins;            // the last evaluation's, one per contact (storage reused)
    std::vector<History> prev, cur, initial;
    std::vector<History> next;               // scratch of the post-Newton update (storage reused)
    std::vector<std::vector<Record>> records;
    V3 omega_bearing{0.0, 0.0, 0.0};      // the bearing's angular velocity (J0), from the probe
    std::vector<FilmInput> film_inputs;  // the last evaluation's, per slice, for a lubricated joint
    FiniteCoefficients finite;                           // the finite film model's a1 ... a9 at this B/D
    V3 torque_correction{0.0, 0.0, 0.0};  // eq. (45), for the torque connector
    V3 initial_axis{0.0, 0.0, 1.0};
    double initial_axial = 0.0;
    long force_calls = 0, post_newton_calls = 0;
    std::string failure;
    double failure_time = 0.0;
    StepControl control;
    const void* group = nullptr;  // the system whose step group the joint reports to (report_growth)
    py::object run_start;  // Python callable, once per run start: returns layout.py RunStart; None: none
    std::vector<WearState> wear;  // per slice (the planar joint: one; empty: no wear), set by the binding set_wear
};

std::vector<JointState> g_joints;
std::vector<long> g_free;  // released slots of g_joints, reused by new_joint

JointState& state(long id) {
    if (id < 0 || id >= static_cast<long>(g_joints.size()) || !g_joints[static_cast<size_t>(id)].in_use) {
        throw std::runtime_error("exuclear kernel: unknown joint id " + std::to_string(id));
    }
    return g_joints[static_cast<size_t>(id)];
}

// Record why the run cannot go on, and stop it (an exception ends Exudyn's solve; mirrors
// JointState._fail of _python_kernel/joint_state.py).  Only for a state that cannot go on (non-finite, a penetration
// beyond the limit that shorter steps do not remove): the message names the joint.
[[noreturn]] void fail(JointState& s, double t, const std::string& message) {
    s.failure = message;
    s.failure_time = t;
    std::string who = s.control.label.empty() ? "" : "joint " + s.control.label + ": ";
    throw std::runtime_error("exuclear: " + who + message + " at t = " + std::to_string(t) +
                             " s (joint.failure() says more)");
}

// JointState.start_run: a new run begins; forget the last run's step control and ask the
// handle (Python, once per run) whether the solver can shorten steps and the joint's name.
void start_run(JointState& s) {
    long runs = s.control.runs + 1;
    s.control = StepControl();
    s.control.runs = runs;
    if (!s.run_start || s.run_start.is_none()) return;
    try {  // the fields of layout.py RunStart, by name (RUN_START_FIELDS)
        py::object r = s.run_start();
        StepControl& c = s.control;
#define READ_FIELD(type, name, value) c.name = r.attr(#name).cast<type>();
        RUN_START_FIELDS(READ_FIELD)
#undef READ_FIELD
        c.jacobian_on = c.jacobian_step < INF;  // steer_newton asked for it at the first step
    } catch (py::error_already_set&) {  // never end a run for a label: keep the defaults
        PyErr_Clear();
    } catch (py::cast_error&) {
    }
}

// JointStepControl.steer_jacobian: ask for a Jacobian per step while the step the joint accepts is
// longer than the run-start callback's jacobian_step (steering.py steer_newton), and for the step after one in
// which a contact opened or closed or that it redoes or grows (step INF); also while a worn
// joint is in contact (conformal: in its imprint the contact's normal, the overlaps' resultant
// of eq. (75), turns fast as the journal moves sideways, which an older Jacobian misses).
// Through its jacobian_per_step(): a call where the ask changes, not per step.
void steer_jacobian(JointState& s, double step, bool conformal = false) {
    bool wanted = conformal || step > s.control.jacobian_step;
    if (wanted == s.control.jacobian_on) return;
    s.control.jacobian_on = wanted;
    if (!s.run_start || s.run_start.is_none()) return;
    try {
        s.run_start.attr("jacobian_per_step")(wanted);
    } catch (py::error_already_set&) {  // never end a run for a Jacobian: the setting stays as it was
        PyErr_Clear();
    }
}

// JointState._call_back: call the run-start callback's method `name` (a warning it issues,
// never an error that would end the run).
void call_back(JointState& s, const char* name) {
    if (!s.run_start || s.run_start.is_none()) return;
    try {
        s.run_start.attr(name)();
    } catch (py::error_already_set&) {  // a warning filter that raises: the notes keep it
        PyErr_Clear();
    }
}

// JointState.tell: the first step of a run that the joint could not resolve (of each kind)
// is told at once, through the run-start callback's `note()` (Python issues the
// AccuracyWarning, with its advice): a run that Exudyn then stops is not silent either.
void tell(JointState& s) { call_back(s, "note"); }

// JointState.tell_end: the accepted step that reaches the run's end time (the run-start record's
// end_time) tells the handle once, through the run-start callback's `finished()`: Python then
// warns of what the whole run left unresolved (its chatter count is complete only now).
void tell_end(JointState& s, double t) {
    StepControl& c = s.control;
    if (c.finished || !(t >= c.end_time * (1.0 - 1e-12))) return;
    c.finished = true;
    call_back(s, "finished");
}

const char* const DIVERGED = "the state became non-finite (NaN or inf); the integration diverged";

struct Pose {  // the journal's centre p and axis u in J0
    V3 p, u;
};

// Whether the joint wears: a joint whose parameters carry a wear (layout.py wear_code), and
// whose profiles set_wear gave, one per slice on the same nodes (CompiledBackend.set_joint).
bool wears(const Params& a, const JointState& s) {
    if (a.wear_surface == WEAR_NONE) return false;
    int n_slices = slice_count(a);
    int nodes = s.wear.empty() ? 0 : s.wear[0].grid.n;
    if (static_cast<int>(s.wear.size()) != n_slices || nodes != a.wear_nodes) {
        throw std::runtime_error("exuclear kernel: joint " + std::to_string(a.id) + " wears " +
                                 std::to_string(n_slices) + " slices on " + std::to_string(a.wear_nodes) +
                                 " nodes but set_wear gave it " + std::to_string(s.wear.size()) + " on " +
                                 std::to_string(nodes));
    }
    return true;
}

// JointState.wear_profiles: the wear profiles of slice k an evaluation at time t uses, as
// history_for chooses the history (read before history_for, which may start a run)
const Profiles& wear_profiles(const JointState& s, double t, size_t k = 0) {
    const WearState& w = s.wear[k];
    if (!s.started || t < s.prev[0].time) return w.initial;
    return t <= s.cur[0].time ? w.previous : w.current;
}

// JointState.joint_kinematics: every contact's kinematics into s.kins; a worn joint's slice is
// the contact of the worn surfaces (eqs. (75), (76)) at time t
Pose joint_kinematics(const Params& a, JointState& s, const V3& displacement, const V3& rotation, const V3& velocity,
                      const V3& angularVelocity, double t) {
    int n_slices = slice_count(a);
    size_t n = contact_count(a);
    if (s.kins.size() != n) s.kins.resize(n);  // once per joint: no allocation per evaluation
    Pose q;
    V3 dv, dw, w_j;
    // the bearing's spin from the probe, where the loads use it (its probe is off otherwise)
    const V3 w_b = a.bearing_motion ? s.omega_bearing : V3{0.0, 0.0, 0.0};
    if (a.joint_type == SPHERICAL) {  // the ball, eqs. (93)-(96); u: the socket frame's z axis
        q.p = displacement;
        q.u = V3{0.0, 0.0, 1.0};
        s.kins[0] = ball_kinematics(a.r_j, a.r_b, q.p, velocity, angularVelocity, w_b);
        return q;
    }
    if (box(a)) {  // the box's corners against the channel's walls (prismatic.py BOX_PAIRS)
        q.p = displacement;
        q.u = V3{0.0, 0.0, 1.0};
        M3 turned = rotation_xyz(rotation[0], rotation[1], rotation[2]);
        size_t i = 0;
        for (int wall = 0; wall < N_BOX_WALLS; ++wall) {
            for (int corner = 0; corner < N_BOX_CORNERS; ++corner) {
                s.kins[i] = box_corner_kinematics(0.5 * a.length, a.r_j, a.half_width, a.r_b, a.channel_half_width,
                                                  corner, wall, q.p, turned, velocity, angularVelocity, w_b);
                leave_guide(s.kins[i++], a.half_guide);
            }
        }
        return q;
    }
    if (a.joint_type == PRISMATIC) {  // the slider's corners in the plane normal to z (prismatic.py PAIRS)
        q.p = V3{displacement[0], displacement[1], 0.0};
        q.u = V3{0.0, 0.0, 1.0};
        size_t i = 0;
        for (int wall = 0; wall < N_WALLS; ++wall) {
            for (int corner = 0; corner < N_CORNERS; ++corner) {
                s.kins[i] = corner_kinematics(0.5 * a.length, a.r_j, a.r_b, corner, wall, displacement[0],
                                              displacement[1], rotation[2], velocity[0], velocity[1],
                                              angularVelocity[2], w_b[2]);
                leave_guide(s.kins[i++], a.half_guide);
            }
        }
        return q;
    }
    if (a.slices == 0) {  // the planar joint: the motion projected on the plane normal to the axis
        q.p = V3{displacement[0], displacement[1], 0.0};
        q.u = V3{0.0, 0.0, 1.0};
        dv = V3{velocity[0], velocity[1], 0.0};
        dw = V3{0.0, 0.0, angularVelocity[2]};
        w_j = V3{0.0, 0.0, w_b[2]};
    } else {
        q.p = displacement;
        q.u = journal_axis(rotation, a.axis_journal);                   // eq. (34)
        dv = velocity;
        dw = angularVelocity;
        w_j = w_b;
    }
    if (a.slices == 0) {  // eqs. (1)-(8): omega_i = dw_z + omega_j, the journal's own spin
        if (a.joint_type == PIN_SLOT) {  // the pin against the slot's centre segment (slot.py); length: the slot's
            s.kins[0] = slot_kinematics(a.r_j, a.r_b, 0.5 * a.length, q.p[0], q.p[1], dv[0], dv[1], dw[2] + w_j[2],
                                        w_j[2]);
        } else {
            s.kins[0] = contact_kinematics(a.r_j, a.r_b, q.p[0], q.p[1], dv[0], dv[1], dw[2] + w_j[2], w_j[2]);
        }
        if (wears(a, s)) {  // psi: the journal's turn about the axis
            s.kins[0] = s.wear[0].kinematics(a, wear_profiles(s, t), s.kins[0], rotation[2], dv[0], dv[1],
                                             dw[2] + w_j[2], w_j[2]);
        }
        if (a.film_model != FILM_NONE) {
            s.film_inputs.resize(1);
            s.film_inputs[0] = FilmInput{q.p[0], q.p[1], dv[0], dv[1], dw[2] + w_j[2], w_j[2]};
        }
    } else {
        for (int k = 0; k < n_slices; ++k) {
            s.kins[static_cast<size_t>(k)] =
                slice_kinematics(a.r_j, a.r_b, slice_centre(a.length, n_slices, k), q.p, q.u, dv, dw, w_j);
        }
        if (wears(a, s)) {  // each slice's worn contact in its plane, psi its turn about the axis (section 11.7)
            for (int k = 0; k < n_slices; ++k) {
                size_t i = static_cast<size_t>(k);
                s.kins[i] = s.wear[i].slice_kinematics(a, wear_profiles(s, t, i), s.kins[i], rotation[2], q.p, q.u, dv,
                                                       dw, w_j);
            }
        }
        if (a.film_model != FILM_NONE) {
            s.film_inputs.resize(static_cast<size_t>(n_slices));
            for (int k = 0; k < n_slices; ++k) {
                s.film_inputs[static_cast<size_t>(k)] =
                    slice_film_input(s.kins[static_cast<size_t>(k)], q.p, q.u, dv, dw, w_j);
            }
        }
    }
    if (a.play > 0.0) {
        for (int f = 0; f < 2; ++f) {
            s.kins[static_cast<size_t>(n_slices + f)] =
                face_kinematics(a.length, a.play, a.friction_radius, FACE_SIDES[f], q.p, q.u, dv, dw, w_j);
        }
    }
    return q;
}

bool all_finite(const JointState& s) {
    for (const Kinematics& k : s.kins) {
        if (!finite(k)) return false;
    }
    return true;
}

// JointState.history_for: the contacts' history an evaluation at time t uses.  A time
// before the last step's start means a new run: forget everything and take this
// evaluation's state (s.kins) as the run's initial accepted state.
const std::vector<History>& history_for(JointState& s, const Params& a, const Pose& q, double t) {
    if (!s.started || t < s.prev[0].time) {
        size_t n = s.kins.size();
        s.initial_axis = q.u;
        s.initial_axial = q.p[2];
        s.records.assign(n, std::vector<Record>());
        s.failure.clear();
        start_run(s);
        for (WearState& w : s.wear) w.reset();
        s.cur.resize(n);
        for (size_t i = 0; i < n; ++i) {
            History fresh;
            fresh.time = t;
            s.cur[i] = accept(fresh, a, contact_kind(a, i), s.kins[i], t, s.records[i]);
        }
        for (size_t i = 0; i < s.film_inputs.size() && a.film_model != FILM_NONE; ++i) {
            set_film_outputs(s.cur[i], film_load(a, s.finite, s.film_inputs[i]), film_share(a));
        }
        s.prev = s.cur;
        s.initial = s.cur;
        s.started = true;
        if (!all_finite(s)) fail(s, t, DIVERGED);
        if (!s.control.refusal.empty()) fail(s, t, s.control.refusal);  // e.g. a journal outside its bearing
    }
    return t <= s.cur[0].time ? s.prev : s.cur;
}

// JointState.accept_wear: the wear of an accepted step of length h [s] ending at t in the states
// s.kins with the contacts' histories `next` (their normal forces; advance: a new step, else one
// computed again, as in post_newton), slice by slice: each with its slip, |v_t| h (planar) or
// |v_s| h (a spatial slice, eq. (42)), and its normal force; stops the run where a profile's
// update would be unstable (eq. (81)).
void accept_wear(const Params& a, JointState& s, bool advance, const std::vector<History>& next, double psi, double h,
                 double t) {
    for (size_t k = 0; k < s.wear.size(); ++k) {
        WearState& w = s.wear[k];
        const Kinematics& kin = s.kins[k];
        double slip = (a.slices == 0 ? std::fabs(kin.v_t) : kin.speed) * h;
        w.accept(a, advance ? w.current : w.previous, w.next, kin, psi, next[k].f_n, slip);
        if (advance) std::swap(w.previous, w.current);  // previous = the old current
        std::swap(w.current, w.next);                    // current = the new profiles; next is scratch
        std::string why = w.unstable(slip, h, a.slices == 0 ? "" : " of slice " + std::to_string(k));
        if (!why.empty()) fail(s, t, why);
    }
}

// JointState.in_worn_contact: whether a slice is in contact on profiles deeper than
// CONFORMAL_DEPTH of its penetration (its contact conformal, section 11.1)
bool in_worn_contact(const JointState& s) {
    for (size_t k = 0; k < s.wear.size(); ++k) {
        const Profiles& p = s.wear[k].current;
        if (s.cur[k].in_contact && p.worn && p.deepest > CONFORMAL_DEPTH * s.cur[k].delta) return true;
    }
    return false;
}

V6 zeros6() { return V6{0.0, 0.0, 0.0, 0.0, 0.0, 0.0}; }

// JointKernel.force_torque: [F; T] in J0, F the force on the bearing (marker 0), T minus the
// journal's moment about its marker point (Exudyn applies +F, +T to the bearing, -F, -T to
// the journal); the bearing's own moment beyond T goes to the torque connector (eq. (45)).
V6 joint_force(const Params& a, double t, const V3& displacement, const V3& rotation, const V3& velocity,
               const V3& angularVelocity) {
    JointState& s = state(a.id);
    s.force_calls++;
    Pose q = joint_kinematics(a, s, displacement, rotation, velocity, angularVelocity, t);
    const std::vector<History>& history = history_for(s, a, q, t);
    double loads[9] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (size_t i = 0; i < s.kins.size(); ++i) {
        const Kinematics& k = s.kins[i];
        if (k.delta <= 0.0) continue;
        ContactKind kind = contact_kind(a, i);
        add_loads(loads, a, kind, q.u, k, response(a, kind, history[i], k));
    }
    if (a.film_model != FILM_NONE) {  // at every eccentricity (section 10.5), on every slice
        for (size_t i = 0; i < s.film_inputs.size(); ++i) {
            FilmLoad r = film_load(a, s.finite, s.film_inputs[i]);
            if (a.slices == 0) {
                add_film_loads(loads, r);
            } else {
                add_film_slice_loads(loads, film_share(a), q.u, s.kins[i], r);
            }
        }
    }
    if (planar(a)) {  // the planar slice's loads hold the bearing's whole moment (eq. (26))
        s.torque_correction = V3{loads[6], loads[7], loads[8]};
    } else {
        V3 force{loads[0], loads[1], loads[2]};
        V3 pf = cross(q.p, force);                                      // eq. (45)
        s.torque_correction = V3{pf[0] + loads[6], pf[1] + loads[7], pf[2] + loads[8]};
    }
    return V6{loads[0], loads[1], loads[2], loads[3], loads[4], loads[5]};
}

void record_bearing_spin(const Params& a, const V3& angularVelocity) {  // the probe: marker 1 is the ground
    state(a.id).omega_bearing = V3{-angularVelocity[0], -angularVelocity[1], -angularVelocity[2]};
}

// Appends a history's data-node entries (layout.DATA_COLUMNS) from entry `first` on.
void data_values(const History& h, StdVector& out, int first = 0) {
    double values[N_DATA] = {h.time, h.delta == -INF ? 0.0 : h.delta, h.delta_dot, h.ex, h.ey, h.f_n, h.f_t, h.v_t,
                             h.v0, h.in_contact ? 1.0 : 0.0, static_cast<double>(h.onsets), h.onset_time,
                             h.peak_force, h.max_penetration};
    for (int i = first; i < N_DATA; ++i) out.push_back(values[i]);
}

}  // namespace
