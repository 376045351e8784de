// Compiled kernel of the exuclear clearance joint: the functions Exudyn calls and the Python
// module (the one translation unit; the headers it includes hold the kernel by role, each
// named as its Python mirror in exuclear/engine/_python_kernel/).
//
// The same formulas as the Python statement of the physics, in the same order and with
// the same names, so that the two can be read side by side and agree to round-off:
//   contact kinematics  exuclear/spatial.py    (docs/physics.md eqs. (33)-(40), (48)-(51); the
//                                               planar joint's eqs. (1)-(8) as one slice),
//                       exuclear/spherical.py  (the spherical joint's ball, eqs. (93)-(96)),
//                       exuclear/prismatic.py  (a slider's corner against a guide's wall),
//                       exuclear/slot.py       (a pin against a slot's centre segment)
//   normal force        exuclear/contact/      (law.py eq. (9) once, damped_normal_force; stiffness.py, damping.py eqs. (10)-(17))
//   friction            exuclear/friction.py   (eqs. (20)-(23))
//   one contact         exuclear/engine/_python_kernel/contacts.py Contact (response: onset velocity,
//                       normal force, friction; the same for slices and end faces)
//   loads               exuclear/spatial.py    (eqs. (41)-(45), (54)); spherical.py (eqs. (97), (98))
//   contact history     exuclear/history.py    (onset velocity, records)
//   film                exuclear/film/         (laws.py, loads.py: eqs. (55)-(70))
//   the joint           exuclear/engine/_python_kernel/joint_state.py JointState (which history an
//                       evaluation uses; force and post-Newton drivers over the contacts)
// The planar joint is the spatial joint with one slice and no end faces, whose motion is
// projected on the plane normal to the bearing axis; the spherical joint (joint_type) has one
// contact, its ball, and the spatial joint's motion.
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

#include "step_control.hpp"

namespace {

V6 force_torque(const MainSystem&, double t, int, V3 displacement, V3 rotation, V3 velocity, V3 angularVelocity,
                M6 parameters, M6 second, M3, M3, V6) {
    Params a = decode(parameters, second);
    switch (a.role) {
        case PROBE:  // marker 0 the bearing, marker 1 the ground: minus the bearing's spin in J0
            record_bearing_spin(a, angularVelocity);
            return zeros6();
        case TORQUE: {
            const V3& c = state(a.id).torque_correction;
            return V6{0.0, 0.0, 0.0, c[0], c[1], c[2]};
        }
        default:
            return joint_force(a, t, displacement, rotation, velocity, angularVelocity);
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
    double redo = impact_redo(a, s, base, t);
    if (!(redo > 0.0)) redo = step_control(a, s, base, t);
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
    tell_end(s, t);
    if (advance) s.prev.swap(s.cur);  // prev = the old cur; base is not read after this
    s.cur.swap(s.next);
    // a worn joint in contact: its conformal contact asks for a Jacobian per step
    bool conformal = worn_joint && in_worn_contact(s);
    steer_jacobian(s, switched ? INF : h, conformal);
    report_growth(s, a.id, system, t, allow, h);
    if (a.joint_type == SPHERICAL) {  // layout.BALL_DATA_COLUMNS: the ball's entries, then its ecc_z
        data_values(s.cur[0], out);
        out.push_back(q.p[2]);
        return out;
    }
    if (a.joint_type == PRISMATIC) {  // layout.pair_data_columns: the time, then each pair's entries
        out.push_back(t);
        for (const History& h : s.cur) data_values(h, out, 1);
        return out;
    }
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

StdVector post_newton(const MainSystem& mbs, double t, int, StdVector data, V3 displacement, V3 rotation,
                      V3 velocity, V3 angularVelocity, M6 parameters, M6 second, M3, M3, V6) {
    Params a = decode(parameters, second);
    if (a.role == PROBE) {
        record_bearing_spin(a, angularVelocity);
        StdVector out = reply(data.size());
        out.insert(out.end(), data.begin(), data.end());
        return out;
    }
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
    m.def("step_control", [](long id) {  // what the joint's own step control holds (layout.py STEP_CONTROL)
        const StepControl& c = state(id).control;
        py::dict d;
#define PUT_FIELD(type, name, value) d[#name] = c.name;
        RUN_START_FIELDS(PUT_FIELD)
        STEP_COUNT_FIELDS(PUT_FIELD)
#undef PUT_FIELD
        return d;
    });
    m.def("dispatch_calls", []() { return g_dispatch_calls; });
    m.def("impact_duration", [](M6 parameters, double mass, double speed) {
        return impact_duration(decode(parameters), mass, speed);
    }, "timescales.impact_duration of the joint whose parameter matrix is given (a test hook)");
    m.def("time_force", [](M6 parameters, V3 displacement, V3 velocity, V3 angularVelocity, double t, long n) {
        // seconds per force_torque evaluation, n evaluations at one state (validation/cost/film.py)
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
    py::list second_layout;
    for (const FieldPosition& f : SECOND_LAYOUT) second_layout.append(py::make_tuple(f.name, f.row, f.column, f.size));
    m.attr("SECOND_LAYOUT") = second_layout;
    py::dict joint_types;  // layout.py JOINT_TYPE_CODES
    joint_types["revolute"] = static_cast<int>(REVOLUTE);
    joint_types["spherical"] = static_cast<int>(SPHERICAL);
    joint_types["prismatic"] = static_cast<int>(PRISMATIC);
    joint_types["pin-slot"] = static_cast<int>(PIN_SLOT);
    m.attr("JOINT_TYPES") = joint_types;
    m.attr("N_DATA") = N_DATA;
    m.attr("N_FILM_DATA") = N_FILM_DATA;
    m.attr("STIFFNESS_CODES") = STIFFNESS_CODES;
    // the step control's fields (layout.py STEP_CONTROL; start_run reads RunStart's by name) and
    // its constants (_python_kernel/step_control.py), which tests keep equal to Python's
    py::list run_start_fields, step_control_fields;
#define NAME_FIELD(type, name, value) run_start_fields.append(#name);
    RUN_START_FIELDS(NAME_FIELD)
#undef NAME_FIELD
#define NAME_FIELD(type, name, value) step_control_fields.append(#name);
    RUN_START_FIELDS(NAME_FIELD)
    STEP_COUNT_FIELDS(NAME_FIELD)
#undef NAME_FIELD
    m.attr("RUN_START_FIELDS") = run_start_fields;
    m.attr("STEP_CONTROL_FIELDS") = step_control_fields;
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
}
