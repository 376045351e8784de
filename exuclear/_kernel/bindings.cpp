// Compiled kernel of the exuclear clearance joint: the functions Exudyn calls and the Python
// module (the one translation unit; the headers it includes hold the kernel by role, each
// named as its Python mirror in exuclear/engine/_python_kernel/).
//
// The same formulas as the Python statement of the physics, in the same order and with
// the same names, so that the two can be read side by side and agree to round-off:
//   contact kinematics  exuclear/spatial.py    (docs/physics.md eqs. (33)-(40), (48)-(51); the
//                                               planar joint's eqs. (1)-(8) as one slice)
//   normal force        exuclear/contact.py    (eq. (9) once, damped_normal_force; eqs. (10)-(17))
//   friction            exuclear/friction.py   (eqs. (20)-(23))
//   one contact         exuclear/engine/_python_kernel/contacts.py Contact (response: onset velocity,
//                       normal force, friction; the same for slices and end faces)
//   loads               exuclear/spatial.py    (eqs. (41)-(45), (54))
//   contact history     exuclear/history.py    (onset velocity, records)
//   film                exuclear/film.py       (eqs. (55)-(70))
//   the joint           exuclear/engine/_python_kernel/joint_state.py JointState (which history an
//                       evaluation uses; force and post-Newton drivers over the contacts)
// The planar joint is the spatial joint with one slice and no end faces, whose motion is
// projected on the plane normal to the bearing axis.
//
// Exudyn calls these functions through raw function pointers, without Python, when they
// are bound by pybind11, capture nothing and have exactly Exudyn's signature
// (see exuclear/engine/kernel.py, which checks that at import).
// Parameters reach the functions through the connector's `stiffness` matrix (layout in
// exuclear/engine/layout.py); the per-joint dynamic state lives in a table indexed by the
// joint id stored there.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <stdexcept>

#include "following.hpp"

namespace {

V6 force_torque(const MainSystem&, double t, int, V3 displacement, V3 rotation, V3 velocity, V3 angularVelocity,
                M6 parameters, M6, M3, M3, V6) {
    Params a = decode(parameters);
    switch (a.role) {
        case PROBE:  // marker 0 the bearing, marker 1 the ground: minus the bearing's spin in J0
            record_bearing_spin(a, angularVelocity);
            return zeros6();
        case TORQUE: {
            const V3& c = state(a.id).torque_correction;
            return V6{0.0, 0.0, 0.0, c[0], c[1], c[2]};
        }
        case CARRIER:  // between two ground markers: no load, only its post-Newton function
            return zeros6();
        default: {
            Follow* f = follow_of(a.id);
            if (f != nullptr) {  // JointKernel.force_torque's following mode
                JointState& s = state(a.id);
                if (!s.started || t < s.prev[0].time) {
                    follow_restart(*f);  // a new run: compliant from its initial state
                } else if (f->active) {  // the condition holds the contact, its friction too: no load
                    s.torque_correction = V3{0.0, 0.0, 0.0};
                    return zeros6();
                }
            }
            return joint_force(a, t, displacement, rotation, velocity, angularVelocity);
        }
    }
}

// The reply of a post-Newton function, [error = 0, recommended step = -1], with room for the
// data node's n entries after it: one allocation per call (Exudyn counts a run's allocations
// and warns where they come every step).
StdVector reply(size_t n) {
    StdVector out;
    out.reserve(2 + n);
    out.push_back(0.0);
    out.push_back(-1.0);
    return out;
}

// The reply that has the solver redo the step at `step` [s] (the data node unchanged), with a
// Jacobian for the step of another length.
StdVector redo_reply(JointState& s, StdVector out, double step, const StdVector& data) {
    steer_jacobian(s, INF);
    out[0] = REDO_STEP_ERROR;
    out[1] = step;
    out.insert(out.end(), data.begin(), data.end());
    return out;
}

// JointKernel.post_newton: the contacts' history update, once per accepted step.
// Returns [error, recommended step, data...].
StdVector joint_post_newton(const Params& a, const void* system, double t, const StdVector& data,
                            const V3& displacement, const V3& rotation, const V3& velocity,
                            const V3& angularVelocity) {
    StdVector out = reply(data.size());
    JointState& s = state(a.id);
    s.post_newton_calls++;
    Pose q = joint_kinematics(a, s, displacement, rotation, velocity, angularVelocity, t);
    history_for(s, a, q, t);  // starts a run if needed
    bool advance = t > s.cur[0].time;
    const std::vector<History>& base = advance ? s.cur : s.prev;  // a repeated step starts again from its start
    if (!all_finite(s)) fail(s, t, DIVERGED);
    size_t n = s.kins.size();
    if (a.impact_step > 0.0 && t - base[0].time > a.impact_step * (1.0 + STEP_SLACK)) {
        bool run_start = base[0].time == s.initial[0].time;  // the step from the run's initial state
        for (size_t i = 0; i < n; ++i) {
            // a contact begins in a long step, or the run begins in an impact: redo it with impact_step
            if ((!base[i].in_contact && s.kins[i].delta > 0.0) ||
                (run_start && base[i].in_contact && std::fabs(base[i].v0) > a.v_min)) {
                return redo_reply(s, std::move(out), a.impact_step, data);
            }
        }
    }
    Follow* f = follow_of(a.id);
    Params rule = a;
    if (f != nullptr && f->active) {  // the condition sets the normal rate: no rate criterion
        rule.rate_limit = 0.0;
        double h = t - base[0].time;
        double redo = follow_hold_step(*f, a, s.kins[0].delta, h, base[0].time, s.control);
        if (!(redo > 0.0)) redo = held_cap(s.control, h, a.impact_step);  // held by the condition: capped too
        if (redo > 0.0) return redo_reply(s, std::move(out), redo, data);
    }
    double redo = step_control(rule, s, base, t);
    if (redo > 0.0) return redo_reply(s, std::move(out), redo, data);
    s.next.resize(n);
    for (size_t i = 0; i < n; ++i) {
        s.records[i].resize(static_cast<size_t>(base[i].closed));
        s.next[i] = accept(base[i], a, contact_kind(a, i), s.kins[i], t, s.records[i]);
        if (!std::isfinite(s.next[i].f_n)) fail(s, t, "the contact force became non-finite (NaN or inf)");
    }
    for (size_t i = 0; i < s.film_inputs.size() && a.film_model != FILM_NONE; ++i) {
        set_film_outputs(s.next[i], film_load(a, s.finite, s.film_inputs[i]), film_share(a));
    }
    bool worn_joint = wears(a, s);
    if (worn_joint) accept_wear(a, s, advance, s.next, rotation[2], t - base[0].time, t);
    // the step before this one: free flight must have lasted both (a repeated step: unknown)
    double allow = advance ? step_growth(a, s.prev, base, s.next, t) : 0.0;
    double h = t - base[0].time;
    bool switched = false;  // a contact opened or closed in this step: its stiffness came or went
    long ended = 0;         // contacts that ended in this step
    for (size_t i = 0; i < n; ++i) {
        switched = switched || base[i].in_contact != s.next[i].in_contact;
        if (base[i].in_contact && !s.next[i].in_contact) ended++;
    }
    count_separations(s.control, advance, ended, h);
    History before = base[0];
    if (advance) s.prev.swap(s.cur);  // prev = the old cur; base is not read after this
    s.cur.swap(s.next);
    if (f != nullptr) {  // the following mode's decisions (FollowState.after_step)
        bool was = f->active;
        follow_after_step(*f, a, s.control, system, t, h, before, s.cur[0]);
        switched = switched || f->active != was;
        if (was && f->active) s.cur[0].f_n = f->multiplier;  // a followed step: the condition's normal force
    }
    // a worn joint in contact: its conformal contact asks for a Jacobian per step
    bool conformal = worn_joint && in_worn_contact(s);
    steer_jacobian(s, switched ? INF : h, conformal);
    report_growth(s, a.id, system, t, allow, h);
    if (a.slices == 0) {  // the planar data node: layout.DATA_COLUMNS (and FILM_DATA_COLUMNS)
        data_values(s.cur[0], out);
        if (a.film_model != FILM_NONE) {
            out.push_back(s.cur[0].film_fx);
            out.push_back(s.cur[0].film_fy);
            out.push_back(s.cur[0].film_torque);
        }
        return out;
    }
    // layout.spatial_data_columns, as many entries as the data node has (reserved by reply)
    out.push_back(t);
    out.push_back(q.u[0]);
    out.push_back(q.u[1]);
    out.push_back(q.p[2]);
    for (const History& h : s.cur) data_values(h, out, 1);  // each contact's entries without its time
    if (a.film_model != FILM_NONE) {  // then each slice's film entries (layout.FILM_DATA_COLUMNS)
        for (size_t i = 0; i < s.film_inputs.size(); ++i) {
            out.push_back(s.cur[i].film_fx);
            out.push_back(s.cur[i].film_fy);
            out.push_back(s.cur[i].film_torque);
        }
    }
    return out;
}

// The carrier's post-Newton function (on while the condition holds the contact and the joint's
// connector is off, engine/following.py): the joint's, with the joint's relative motion from the
// condition's last evaluation (carried_motion); nothing in the sweep in which the joint's own
// post-Newton switched the condition on (that step is done).  The planar joint only: its turn
// (`rotation`) enters only wear, which the following mode excludes.
StdVector carrier_post_newton(const Params& a, const void* system, double t, const StdVector& data) {
    Follow* f = follow_of(a.id);
    V3 displacement, velocity, angular;
    if (f == nullptr || !f->active || t == f->carrier_skip_time) {
        if (f != nullptr) f->carrier_skip_time = NAN;
        StdVector out = reply(data.size());
        out.insert(out.end(), data.begin(), data.end());
        return out;
    }
    if (!carried_motion(*f, t, displacement, velocity, angular)) {
        fail(state(a.id), t, "the following mode's condition was not evaluated at the step's end");
    }
    Params joint = a;
    joint.role = MAIN;
    return joint_post_newton(joint, system, t, data, displacement, V3{0.0, 0.0, 0.0}, velocity, angular);
}

StdVector post_newton(const MainSystem& mbs, double t, int, StdVector data, V3 displacement, V3 rotation,
                      V3 velocity, V3 angularVelocity, M6 parameters, M6, M3, M3, V6) {
    Params a = decode(parameters);
    if (a.role == PROBE) {
        record_bearing_spin(a, angularVelocity);
        StdVector out = reply(data.size());
        out.insert(out.end(), data.begin(), data.end());
        return out;
    }
    if (a.role == CARRIER) return carrier_post_newton(a, &mbs, t, data);
    return joint_post_newton(a, &mbs, t, data, displacement, rotation, velocity, angularVelocity);
}

// ---- dispatch counter for the self-test -----------------------------------------------------
long g_dispatch_calls = 0;
struct DispatchCounter {  // constructed only when a call comes through pybind11's Python dispatcher
    DispatchCounter() { ++g_dispatch_calls; }
};

py::dict history_dict(const History& h) {
    py::dict d;
    d["time"] = h.time;
    d["delta"] = h.delta;
    d["delta_dot"] = h.delta_dot;
    d["in_contact"] = h.in_contact;
    d["v0"] = h.v0;
    d["onsets"] = h.onsets;
    d["closed"] = h.closed;
    d["onset_time"] = h.onset_time;
    d["peak_force"] = h.peak_force;
    d["max_penetration"] = h.max_penetration;
    d["normal_force"] = h.f_n;
    d["tangential_force"] = h.f_t;
    d["slip_velocity"] = h.v_t;
    d["ecc_x"] = h.ex;
    d["ecc_y"] = h.ey;
    d["film_fx"] = h.film_fx;
    d["film_fy"] = h.film_fy;
    d["film_torque"] = h.film_torque;
    return d;
}

py::list history_list(const std::vector<History>& hs) {
    py::list l;
    for (const History& h : hs) l.append(history_dict(h));
    return l;
}

}  // namespace

PYBIND11_MODULE(_ckernel, m) {
    m.doc() = "Compiled kernel of the exuclear clearance joint (see exuclear/engine/kernel.py)";
    m.def("force_torque", &force_torque, py::call_guard<DispatchCounter>(),
          "springForceTorqueUserFunction of the clearance-joint connectors");
    m.def("post_newton", &post_newton, py::call_guard<DispatchCounter>(),
          "postNewtonStepUserFunction of the clearance-joint connectors");
    m.def("new_joint", []() {
        if (!g_free.empty()) {  // reuse a released slot
            long id = g_free.back();
            g_free.pop_back();
            g_joints[static_cast<size_t>(id)] = JointState();
            return id;
        }
        g_joints.emplace_back();
        return static_cast<long>(g_joints.size() - 1);
    }, "a new joint's id in the kernel's table");
    m.def("release", [](long id) {
        forget_follow(id);
        leave_group(state(id));
        state(id) = JointState();
        g_joints[static_cast<size_t>(id)].in_use = false;
        g_free.push_back(id);
    }, "free a joint's state (its handle is gone); new_joint reuses the slot");
    m.def("joints_in_use", []() { return static_cast<long>(g_joints.size() - g_free.size()); });
    m.def("reset", [](long id) {  // forget the history; keep the run-start callback and the run count
        JointState& s = state(id);
        py::object run_start = s.run_start;
        long runs = s.control.runs;
        std::vector<WearState> wear = std::move(s.wear);  // the joint's wear (set_wear) stays, back at its initial profiles
        leave_group(s);
        s = JointState();
        s.run_start = run_start;
        s.control.runs = runs;
        s.wear = std::move(wear);
        for (WearState& w : s.wear) w.reset();
        if (Follow* f = follow_of(id)) follow_restart(*f);
    });
    m.def("set_wear", [](long id, std::vector<std::vector<double>> bearing, std::vector<std::vector<double>> journal,
                         double e_star, double length) {
        // the profiles a joint's wear starts from, one row per slice (the planar joint: one;
        // exuclear.Wear's bearing and journal, or zeros; none: the joint does not wear), the law's
        // E* for the Hertz strip and the length [m] each row stands for (L, a slice's L / N); the
        // joint's worn profiles so far are forgotten, as the Python kernel's joint setter does
        if (bearing.size() != journal.size()) throw std::invalid_argument("set_wear: profiles of different slices");
        std::vector<WearState>& wear = state(id).wear;
        wear.clear();
        for (size_t k = 0; k < bearing.size(); ++k) {
            if (bearing[k].size() != journal[k].size()) throw std::invalid_argument("set_wear: profiles of different nodes");
            WearState w;
            w.grid = grid(static_cast<int>(bearing[k].size()));
            w.e_star = e_star;
            w.length = length;
            size_t n = bearing[k].size();
            w.initial = Profiles{bearing[k], journal[k], std::vector<double>(n, 0.0), std::vector<double>(n, 0.0), false};
            w.initial.update_worn();
            w.reset();
            wear.push_back(std::move(w));
        }
    }, "a joint's wear: its initial profiles [m] per slice (none: no wear), E* [Pa] and the slice's length [m] "
       "(CompiledBackend.set_joint)");
    m.def("wear_profiles", [](long id) {  // per slice, after the last accepted step (before a run: the initial ones)
        py::dict d;
        py::list bearing, journal, slip, stability;
        for (const WearState& w : state(id).wear) {
            bearing.append(py::cast(w.current.bearing));
            journal.append(py::cast(w.current.journal));
            slip.append(py::cast(w.current.slip));
            stability.append(py::cast(w.current.stability));
        }
        d["bearing"] = bearing;
        d["journal"] = journal;
        d["slip"] = slip;
        d["stability"] = stability;
        return d;
    });
    m.attr("SLICE_WEAR") = true;  // the spatial joint wears per slice (arguments.kernel_has_wear)
    m.def("set_run_start", [](long id, py::object callback) { state(id).run_start = callback; },
          "a callable called once per run start, returning layout.py's RunStart; hold no strong "
          "reference to the joint's handle in it");
    m.def("step_control", [](long id) {  // what the joint's own step control did in the last run
        const StepControl& c = state(id).control;
        py::dict d;
        d["runs"] = c.runs;
        d["can_shorten"] = c.can_shorten;
        d["min_step"] = c.min_step;
        d["rate"] = c.rate;
        d["label"] = c.label;
        d["group_size"] = c.group_size;
        d["rate_scale"] = c.rate_scale;
        d["growth_cap"] = c.growth_cap;
        d["contact_cap"] = c.contact_cap;
        d["jacobian_step"] = c.jacobian_step;
        d["jacobian_on"] = c.jacobian_on;
        d["separation_step"] = c.separation_step;
        d["impact_mass"] = c.impact_mass;
        d["separations"] = c.separations;
        d["long_separations"] = c.long_separations;
        d["rejected"] = c.rejected;
        d["unresolved"] = c.unresolved;
        d["held_long"] = c.held_long;
        d["held_time"] = c.held_time;
        d["held_step"] = c.held_step;
        d["unresolved_time"] = c.unresolved_time;
        d["unresolved_step"] = c.unresolved_step;
        d["unresolved_advice"] = c.unresolved_advice;
        d["over_limit"] = c.over_limit;
        d["over_time"] = c.over_time;
        d["over_step"] = c.over_step;
        d["deepest"] = c.deepest;
        return d;
    });
    m.def("dispatch_calls", []() { return g_dispatch_calls; });
    m.def("follow_constraint", &condition_constraint, py::call_guard<DispatchCounter>(),
          "constraintUserFunction of a followed joint's condition (ObjectConnectorCoordinateVector)");
    m.def("follow_jacobian", &condition_jacobian, py::call_guard<DispatchCounter>(),
          "jacobianUserFunction of a followed joint's condition");
    m.def("set_follow", [](long id, int item, py::object events, int kind0, V3 local0, M3 frame0, int kind1,
                           V3 local1) {
        // the following mode of joint `id`: its condition's object number, the Python object the
        // kernel tells of events (exuclear.engine.following.CompiledEvents) and the condition's two
        // sides (following.hpp ConditionSide: kind, the marker's position in the body, and for the
        // bearing the joint frame J0 in its body, rows)
        state(id);
        for (int kind : {kind0, kind1}) {
            if (kind < SIDE_GROUND || kind >= SIDE_KINDS) throw std::invalid_argument("set_follow: unknown side kind");
        }
        Follow f;
        f.item = item;
        f.events = events;
        f.sides[0] = ConditionSide{kind0, local0, V3{frame0[0][2], frame0[1][2], frame0[2][2]}, frame0};
        f.sides[1] = ConditionSide{kind1, local1, V3{0.0, 0.0, 1.0}};
        forget_follow(id);
        g_follow[id] = f;
    }, "a joint's compiled following mode (exuclear.engine.following)");
    m.def("follow_counts", [](long id) {  // FollowState.counts
        py::dict d;
        Follow* f = follow_of(id);
        if (f == nullptr) return d;
        d["on"] = f->on_count;
        d["off"] = f->off_count;
        d["lost"] = f->lost;
        d["redone"] = f->redone;
        d["followed_steps"] = f->followed_steps;
        d["active"] = f->active || f->parked;
        return d;
    });
    m.def("impact_duration", [](M6 parameters, double mass, double speed) {
        return impact_duration(decode(parameters), mass, speed);
    }, "timescales.impact_duration of the joint whose parameter matrix is given (a test hook)");
    m.def("time_force", [](M6 parameters, V3 displacement, V3 velocity, V3 angularVelocity, double t, long n) {
        // seconds per force_torque evaluation, n evaluations at one state (validation/film_cost.py)
        V3 rotation{0.0, 0.0, 0.0};
        volatile double sink = 0.0;  // keeps the evaluations from being optimised away
        auto start = std::chrono::steady_clock::now();
        for (long i = 0; i < n; ++i) {  // what force_torque does for the joint's connector: decode, evaluate
            Params a = decode(parameters);
            V6 f = joint_force(a, t, displacement, rotation, velocity, angularVelocity);
            sink = sink + f[0];
        }
        std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
        return elapsed.count() / static_cast<double>(n);
    }, "seconds per evaluation of the joint's force function (a micro benchmark)");
    m.def("calls", [](long id) {
        JointState& s = state(id);
        return py::make_tuple(s.force_calls, s.post_newton_calls);
    });
    m.def("history", [](long id) {  // per contact: slices (one for the planar joint), then end faces
        JointState& s = state(id);
        py::dict d;
        d["started"] = s.started;
        d["current"] = history_list(s.cur);
        d["previous"] = history_list(s.prev);
        d["initial"] = history_list(s.initial);
        return d;
    });
    m.def("records", [](long id) {  // per contact
        JointState& s = state(id);
        py::list out;
        for (const std::vector<Record>& rs : s.records) {
            py::list l;
            for (const Record& r : rs) {
                l.append(py::make_tuple(r.onset_time, r.onset_velocity, r.peak_force, r.duration, r.max_penetration));
            }
            out.append(l);
        }
        return out;
    });
    m.def("initial_axis", [](long id) {
        JointState& s = state(id);
        return py::make_tuple(py::make_tuple(s.initial_axis[0], s.initial_axis[1], s.initial_axis[2]),
                              s.initial_axial);
    });
    m.def("failure", [](long id) {
        JointState& s = state(id);
        return py::make_tuple(s.failure, s.failure_time);
    });
    m.def("failed", [](long id) { return !state(id).failure.empty(); });  // per step, cheap: no string
    py::list layout;
    for (const FieldPosition& f : LAYOUT) layout.append(py::make_tuple(f.name, f.row, f.column, f.size));
    m.attr("LAYOUT") = layout;
    m.attr("N_DATA") = N_DATA;
    m.attr("N_FILM_DATA") = N_FILM_DATA;
    m.attr("STIFFNESS_CODES") = STIFFNESS_CODES;
    // the run-start record's fields start_run reads (layout.py RunStart), and the step
    // control's constants (_python_kernel/step_control.py), which tests keep equal to Python's
    py::list run_start_fields;
    for (const char* name : {"can_shorten", "min_step", "label", "rate", "group_size", "rate_scale", "growth_cap",
                             "contact_cap", "jacobian_step", "separation_step", "impact_mass"}) {
        run_start_fields.append(name);
    }
    m.attr("RUN_START_FIELDS") = run_start_fields;
    py::dict constants;
    constants["REDO_STEP_ERROR"] = REDO_STEP_ERROR;
    constants["STEP_SLACK"] = STEP_SLACK;
    constants["ONSET_TAIL"] = ONSET_TAIL;
    constants["ONSET_TARGET"] = ONSET_TARGET;
    constants["ONSET_FLOOR"] = ONSET_FLOOR;
    constants["ONSET_IDLE_STEPS"] = ONSET_IDLE_STEPS;
    constants["SOLVER_STEP_CUT"] = SOLVER_STEP_CUT;
    constants["STEP_SAFETY"] = STEP_SAFETY;
    constants["MAX_CUT"] = MAX_CUT;
    constants["MIN_STEP_MARGIN"] = MIN_STEP_MARGIN;
    constants["GROWTH_LIMIT"] = GROWTH_LIMIT;
    constants["GROWTH_MIN"] = GROWTH_MIN;
    constants["GROWTH_GAP"] = GROWTH_GAP;
    constants["PENETRATION_CUT"] = PENETRATION_CUT;
    constants["PENETRATION_RETRIES"] = PENETRATION_RETRIES;
    m.attr("STEP_CONSTANTS") = constants;
    py::dict follow;  // the following mode's rules (_python_kernel/following.py), which tests keep equal
    follow["FOLLOW_PERIODS"] = FOLLOW_PERIODS;
    follow["FOLLOW_STEP"] = FOLLOW_STEP;
    follow["FOLLOW_TURN"] = FOLLOW_TURN;
    follow["FOLLOW_HOLD"] = FOLLOW_HOLD;
    follow["FOLLOW_HOLD_FRICTION"] = FOLLOW_HOLD_FRICTION;
    follow["HOLD_REDOS"] = HOLD_REDOS;
    follow["FOLLOW_MIN_STEPS"] = FOLLOW_MIN_STEPS;
    follow["FOLLOW_RATE"] = FOLLOW_RATE;
    follow["FOLLOW_GAIN"] = FOLLOW_GAIN;
    follow["GA_BETA"] = GA_BETA;
    follow["FOLLOW_DEAD_BAND"] = FOLLOW_DEAD_BAND;
    follow["FOLLOW_FILTER"] = FOLLOW_FILTER;
    follow["FOLLOW_ATOL_SHARE"] = FOLLOW_ATOL_SHARE;
    follow["FOLLOW_ATOL_FORCE"] = FOLLOW_ATOL_FORCE;
    follow["DAMPED_RTOL"] = DAMPED_RTOL;
    follow["DAMPED_MAX_ITER"] = DAMPED_MAX_ITER;
    follow["DAMPED_FIRST"] = DAMPED_FIRST;
    follow["END_SLACK"] = END_SLACK;
    follow["STICK_MARGIN"] = STICK_MARGIN;
    follow["RATE_GAIN"] = RATE_GAIN;
    follow["PENETRATION_RTOL"] = PENETRATION_RTOL;
    follow["PENETRATION_MAX_ITER"] = PENETRATION_MAX_ITER;
    m.attr("FOLLOW_SIDE_KINDS") = py::make_tuple("ground", "rigid 2D", "rigid Euler parameters",
                                                "rigid Tait-Bryan angles", "rigid rotation vector (Lie group)");  // SideKind
    m.attr("FOLLOW_CONSTANTS") = follow;
}
