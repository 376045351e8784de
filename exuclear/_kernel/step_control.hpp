// The joint's own step control: a step longer than the joint's impact_step in which an impact
// begins is redone at it (impact_redo); a step in which a contact begins too early or the
// penetration rate changes too much is redone shorter (step_control), free flight lets the next step grow
// (step_growth, report_growth, over a system's step group), and the contacts that ended in
// too long a step are counted (count_separations).  Python:
// exuclear/engine/_python_kernel/step_control.py.

#pragma once

#include <sstream>

#include "joint_state.hpp"

namespace {

// Error a post-Newton function returns to make Exudyn redo a step (above its
// discontinuous.iterationTolerance, default 1).
const double REDO_STEP_ERROR = 1e3;
// Relative slack on a step length compared with impact_step (Exudyn's steps carry round-off).
const double STEP_SLACK = 1e-9;

// ---- the joint's own step control (_python_kernel/step_control.py JointStepControl.step_control) -------------
// The fraction of a step a contact may have begun before the step's end without a redo: a
// contact that began deeper inside the step is redone so that it begins in the step's last
// ONSET_TARGET (its force then acts from about its onset on, as in the exact path): an implicit
// method charges the force at the step's end over the whole step (_python_kernel/step_control.py has the
// numbers that set these values).
const double ONSET_TAIL = 0.02;
const double ONSET_TARGET = 0.01;
// A contact that began in the step's first ONSET_FLOOR (touching at its start) is resolved
// from its start: it is not redone (that would shrink the step towards zero); the rate
// criterion resolves the rest.
const double ONSET_FLOOR = 0.05;
// ... and only in a step longer than the impact's duration (impact_duration at the joint's
// effective mass) over ONSET_IDLE_STEPS: a step that resolves the impact stays as the user chose
// it (a redo there shortens the compression's steps only, and the errors of compression and
// restitution no longer cancel; docs/validation/step_control.md has the numbers).
const double ONSET_IDLE_STEPS = 12.0;
// Exudyn's implicit solver redoes a rejected step with at most this fraction of it
// (ReduceStepSize: the smaller of 0.75 h and the recommendation): see onset_step.
const double SOLVER_STEP_CUT = 0.75;
// The recommended step's margin below the estimate (the change of the penetration rate is
// not linear in the step: aim a little short, so that the redone step is accepted).
const double STEP_SAFETY = 0.8;
// The rate criterion shortens a step at most this much per attempt (a step still too long is
// rejected again): the change of the rate is far from linear in a long step, and a larger
// cut overshoots towards the solver's minimum step, where Exudyn's Newton fails.
const double MAX_CUT = 0.1;
// ... and never below this many times the solver's minimum step, near which Exudyn's Newton
// iteration fails (its residual falls to round-off): there the step is accepted and reported.
const double MIN_STEP_MARGIN = 10.0;
// Free flight lets the step grow (_python_kernel/step_control.py JointStepControl.step_growth): after two accepted
// steps in which none of the joint's contacts touched, the next step may last until the journal
// would reach the wall at its present penetration rate and its change, up to GROWTH_LIMIT times
// the step, and only where that is GROWTH_MIN times the step or more (Exudyn's own rule doubles
// a step after 10 steps of at most 7 Newton iterations; with an impact_step, every
// recovery_steps steps).
const double GROWTH_LIMIT = 10.0;
const double GROWTH_MIN = 2.0;
// ... and only where every contact's gap exceeds GROWTH_GAP of the clearance (a journal resting
// on the wall hovers, opening by nanometres, and a longer step there shakes it off)
const double GROWTH_GAP = 1e-2;
// A penetration beyond the joint's limit redoes the step with this fraction of it ...
const double PENETRATION_CUT = 0.25;
// ... this many times for one contact, counted from a step that starts out of contact (the
// step 4^4 = 256 times shorter); a penetration still beyond the limit then is the contact's,
// not the step's: the step is accepted, the joint's failure() says so and the handle warns
// (exuclear.simulate stops the run there).  Counted per step instead, a contact whose
// penetration passes the limit would be approached in ever shorter steps down to the
// solver's minimum step.
const int PENETRATION_RETRIES = 4;

std::string fmt(double x) {
    std::ostringstream o;
    o.precision(4);
    o << x;
    return o.str();
}

// _python_kernel/step_control.py _same: x is y up to STEP_SLACK; an unset time (-INF) matches itself only,
// never a finite time
bool same(double x, double y) {
    return x == y || (std::isfinite(y) && std::fabs(x - y) <= STEP_SLACK * std::fabs(y) + 1e-300);
}

// _python_kernel/step_control.py onset_step: the step that lets a contact begun at `share` of the step h begin in
// the last ONSET_TARGET of a step: of this one, or of the second of two equal steps (SOLVER_STEP_CUT)
double onset_step(double h, double share) {
    double steps = share / (1.0 - ONSET_TARGET) <= SOLVER_STEP_CUT ? 1.0 : 2.0;
    return h * share / (steps - ONSET_TARGET);
}

// JointStepControl._resolves_impact: whether a step h resolves an impact at v0 (false: mass unknown)
bool resolves_impact(const Params& a, const StepControl& c, double h, double v0) {
    double mass = c.impact_mass;
    if (!(mass > 0.0 && std::isfinite(mass))) return false;
    return h * ONSET_IDLE_STEPS <= impact_duration(a, mass, v0);
}

// JointStepControl.impact_redo: where the joint has an impact_step and the step [base.time, t] is
// longer, the step to redo it with (impact_step) when an impact begins in it: a contact begins, or
// it is the run's first step and the run begins in an impact (|v0| > v_min); else 0.
double impact_redo(const Params& a, const JointState& s, const std::vector<History>& base, double t) {
    if (!(a.impact_step > 0.0 && t - base[0].time > a.impact_step * (1.0 + STEP_SLACK))) return 0.0;
    bool run_start = base[0].time == s.initial[0].time;  // the step from the run's initial state
    for (size_t i = 0; i < s.kins.size(); ++i) {
        if ((!base[i].in_contact && s.kins[i].delta > 0.0) ||
            (run_start && base[i].in_contact && std::fabs(base[i].v0) > a.v_min)) {
            return a.impact_step;
        }
    }
    return 0.0;
}

double rate_control(const Params& a, JointState& s, const std::vector<History>& base, double t, double h,
                    bool shortens);

// Whether the step [base.time, t] resolves the joint's contacts; 0: yes (accept it), else the
// shorter step to redo it with.  A step the solver cannot shorten (its settings forbid it, its
// minimum step, or the same step came back unshortened) is accepted and counted for the
// handle's warning, as is a penetration beyond the limit that shorter steps do not remove.
//   onset: a contact with an impact velocity (|v0| > v_min) that began before the step's last
//          ONSET_TAIL, in a step longer than the impact needs (ONSET_IDLE_STEPS): redone to begin
//          at the end of a step (onset_step);
//   rate:  |delta_dot_end - delta_dot_start| > KAPPA max(|v0|, v_min) in a contact (or one that
//          began or ended in the step): several steps per velocity reversal, with neither the
//          mass nor the law in the criterion.  Settled contacts (|v0| at the v_min floor) are
//          limited too (exempting them left 5x simulate's penetration on the zoo's piston
//          engine, and more steps; _python_kernel/step_control.py step_control has the numbers);
//   held:  a step through which a contact is held (in contact at both ends), longer than
//          contact_cap (steering.py HELD_CONTACT_PERIODS contact periods), is redone at it;
//   separation: a step in which a contact ends, longer than separation_step (a tenth of the
//          contact period, steering.py separation_step), is redone at it: a contact that opens
//          in a longer implicit step rings and may close again without a physical cause.
double step_control(const Params& a, JointState& s, const std::vector<History>& base, double t) {
    StepControl& c = s.control;
    double h = t - base[0].time;
    if (!(h > 0.0)) return 0.0;
    bool repeated = same(t, c.last_time) && same(h, c.last_step);  // the solver did not shorten it
    bool shortens = c.can_shorten && !repeated && h > c.min_step * (1.0 + STEP_SLACK);
    double deepest = -INF;
    for (const Kinematics& k : s.kins) deepest = k.delta > deepest ? k.delta : deepest;
    if (deepest > a.max_penetration) {
        bool touching = false;
        for (const History& b : base) touching = touching || b.in_contact;
        if (!same(base[0].time, c.retry_start) && !touching) {  // a new contact: its own retries
            c.retry_start = base[0].time;
            c.retries = 0;
        }
        if (shortens && c.retries < PENETRATION_RETRIES) {
            c.retries++;
            c.rejected++;
            c.last_time = t;
            c.last_step = h;
            double h_new = h * PENETRATION_CUT;
            return h_new > c.min_step ? h_new : c.min_step * (1.0 + STEP_SLACK);
        }
    }
    double h_new = rate_control(a, s, base, t, h, shortens);
    if (deepest > a.max_penetration && h_new == 0.0) {
        // accepted beyond the limit: the run goes on, the handle says so (a simulate run
        // stops); a step the rate rules redo is judged again when it comes back
        if (c.over_limit == 0) {
            c.over_time = t;
            c.over_step = h;
            s.failure = "penetration " + fmt(deepest) + " m exceeds the limit " + fmt(a.max_penetration) + " m";
            s.failure_time = t;
        }
        c.over_limit++;
        c.deepest = deepest > c.deepest ? deepest : c.deepest;
        if (c.over_limit == 1) tell(s);
    }
    return h_new;
}

// _python_kernel/step_control.py JointStepControl._rate_control: the onset, rate, held and separation rules of
// step_control for the step h ending at t: 0 to accept it, else the shorter step to redo it with.
double rate_control(const Params& a, JointState& s, const std::vector<History>& base, double t, double h,
                    bool shortens) {
    StepControl& c = s.control;
    // an explicit impact_step overrides the rate criterion (the caller resolves contacts so)
    double kappa = c.rate && !(a.impact_step > 0.0) ? a.rate_limit * c.rate_scale : 0.0;
    if (!(kappa > 0.0)) return 0.0;
    double h_rec = INF;
    double h_need = INF;  // the rate criterion's estimate without the cap: the advice of a note
    bool rate_exceeded = false;
    bool held_over = false;  // a held contact through a step longer than contact_cap
    for (size_t i = 0; i < s.kins.size(); ++i) {
        const Kinematics& k = s.kins[i];
        const History& b = base[i];
        if (k.delta <= 0.0 && !b.in_contact) continue;  // free flight: nothing limits the step
        bool onset = !b.in_contact;
        double v0 = onset ? onset_velocity(b, k.delta, k.delta_dot) : b.v0;
        bool impact = std::fabs(v0) > a.v_min;
        if (impact && onset && b.delta != -INF && !resolves_impact(a, c, h, v0)) {
            double share = b.delta / (b.delta - k.delta);  // the onset's fraction of the step
            if (1.0 - share > ONSET_TAIL && share > ONSET_FLOOR) {
                double h_on = onset_step(h, share);
                h_rec = h_on < h_rec ? h_on : h_rec;
            }
        }
        if (b.in_contact && k.delta > 0.0 && h > c.contact_cap * (1.0 + STEP_SLACK)) {
            h_rec = c.contact_cap < h_rec ? c.contact_cap : h_rec;  // a held contact: HELD_CONTACT_PERIODS
            held_over = true;
        }
        if (b.in_contact && k.delta <= 0.0 && h > c.separation_step * (1.0 + STEP_SLACK)) {
            h_rec = c.separation_step < h_rec ? c.separation_step : h_rec;  // a contact that opens: resolved
        }
        double change = std::fabs(k.delta_dot - b.delta_dot);
        double allowed = kappa * (impact ? std::fabs(v0) : a.v_min);
        if (change > allowed) {
            double h_rate = STEP_SAFETY * h * allowed / change;
            if (impact) h_need = h_rate < h_need ? h_rate : h_need;
            h_rate = h_rate > MAX_CUT * h ? h_rate : MAX_CUT * h;
            h_rec = h_rate < h_rec ? h_rate : h_rec;
            // reported only for an impact: a settled contact's rate at a fixed step is the load's
            // (the resting pendulum of tests/test_robust.py is right at its fixed step)
            rate_exceeded = rate_exceeded || impact;
        }
    }
    if (h_rec == INF) return 0.0;
    double floor = MIN_STEP_MARGIN * c.min_step;
    if (h_rec < floor) h_rec = floor;
    if (shortens && h > floor * (1.0 + STEP_SLACK)) {
        c.rejected++;
        c.last_time = t;
        c.last_step = h;
        return h_rec > c.min_step ? h_rec : c.min_step * (1.0 + STEP_SLACK);
    }
    if (held_over) {  // accepted through a held contact longer than the cap: say so
        if (c.held_long == 0) {
            c.held_time = t;
            c.held_step = h;
        }
        c.held_long++;
        if (c.held_long == 1) tell(s);
    }
    if (rate_exceeded) {  // accepted unresolved: say so after the run
        if (c.unresolved == 0) {
            c.unresolved_time = t;
            c.unresolved_step = h;
        }
        c.unresolved++;
        h_need = h_need > floor ? h_need : floor;
        c.unresolved_advice = h_need < c.unresolved_advice ? h_need : c.unresolved_advice;
        if (c.unresolved == 1) tell(s);  // with its advice
    }
    return 0.0;
}

// _python_kernel/step_control.py time_to_wall: the smallest positive root of delta + delta_dot tau + delta_ddot tau^2 / 2
double time_to_wall(double delta, double delta_dot, double delta_ddot) {
    if (delta_ddot == 0.0) return delta_dot > 0.0 ? -delta / delta_dot : INF;
    double disc = delta_dot * delta_dot - 2.0 * delta_ddot * delta;
    if (disc < 0.0) return INF;  // moving away and slowing down towards the wall: it turns before it
    double q = delta_dot + std::copysign(std::sqrt(disc), delta_dot != 0.0 ? delta_dot : 1.0);
    double r1 = q != 0.0 ? -2.0 * delta / q : INF, r2 = -q / delta_ddot;
    double best = INF;
    if (r1 > 0.0) best = r1;
    if (r2 > 0.0 && r2 < best) best = r2;
    return best;
}

// JointStepControl.step_growth: the next step the joint's free flight allows after the accepted step
// from base to end, the step before it starting at `before` (0: it asks for none).
double step_growth(const Params& a, const std::vector<History>& before, const std::vector<History>& base,
                   const std::vector<History>& end, double t) {
    const StepControl& c = state(a.id).control;
    double h = t - base[0].time;
    if (!(c.can_shorten && c.rate && a.rate_limit > 0.0 && a.film_model == FILM_NONE && h > 0.0)) {
        return 0.0;
    }
    double allow = GROWTH_LIMIT * h < c.growth_cap ? GROWTH_LIMIT * h : c.growth_cap;
    const double gap = GROWTH_GAP * (a.r_b - a.r_j);
    for (size_t i = 0; i < end.size(); ++i) {
        const History& e = end[i];
        if (before[i].in_contact || base[i].in_contact || e.in_contact || -e.delta < gap) return 0.0;
        if (e.delta == -INF) continue;  // no wall under it (a corner beyond its guide's end): it limits nothing
        double to_wall = time_to_wall(e.delta, e.delta_dot, (e.delta_dot - base[i].delta_dot) / h);
        allow = to_wall < allow ? to_wall : allow;
    }
    return allow >= GROWTH_MIN * h ? allow : 0.0;
}

// The step group of a system (JointStepControl.report_growth): the time of the step its joints report
// on, the smallest allowance reported for it, which joints did, and how many joints belong to it.
struct StepGroup {
    double t = -INF;
    double allow = INF;
    std::vector<long> reported;
    long members = 0;
};
std::unordered_map<const void*, StepGroup> g_groups;  // by the address of the joints' MainSystem

void leave_group(JointState& s) {
    if (s.group == nullptr) return;
    auto it = g_groups.find(s.group);
    if (it != g_groups.end() && --it->second.members <= 0) g_groups.erase(it);
    s.group = nullptr;
}

// JointStepControl.report_growth: the last of a system's joints to report on a step lets the solver's
// next step grow to the smallest allowance, through the run-start callback's grow().
void report_growth(JointState& s, long id, const void* system, double t, double allow, double h) {
    if (!s.run_start || s.run_start.is_none()) return;
    if (s.group != system) {
        leave_group(s);
        s.group = system;
        g_groups[system].members++;
    }
    StepGroup& g = g_groups[system];
    if (g.t != t) {
        g.t = t;
        g.allow = INF;
        g.reported.clear();
    }
    g.allow = allow < g.allow ? allow : g.allow;
    if (std::find(g.reported.begin(), g.reported.end(), id) == g.reported.end()) g.reported.push_back(id);
    if (static_cast<int>(g.reported.size()) == s.control.group_size && g.allow >= GROWTH_MIN * h) {
        steer_jacobian(s, INF);  // the grown step: a Jacobian for it
        try {
            s.run_start.attr("grow")(g.allow);
        } catch (py::error_already_set&) {  // never end a run for a longer step: Exudyn's own rule
            PyErr_Clear();
        }
    }
}

// JointStepControl.count_separations: the contacts that ended in an accepted step of length h, and
// those of them in a step longer than separation_step; a step accepted again from the same
// start (redone after another item rejected it) replaces its first count.
void count_separations(StepControl& c, bool advance, long ended, double h) {
    if (!advance) {
        c.separations -= c.last_ended;
        c.long_separations -= c.last_long;
    }
    c.last_ended = ended;
    c.last_long = h > c.separation_step * (1.0 + STEP_SLACK) ? ended : 0;
    c.separations += c.last_ended;
    c.long_separations += c.last_long;
}

}  // namespace
