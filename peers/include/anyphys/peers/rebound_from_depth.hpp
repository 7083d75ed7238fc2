#pragma once
// The rebound speed to give an engine that finds an impact only once the bodies overlap: shared
// by ODE, Bullet and Box2D's main solve, which all bounce a pair in the step that finds it and
// move it with the rebound speed in that same step (semi-implicit Euler). And which bodies' gravity
// a bounce counts, shared by every backend (fellFreely).
#include <algorithm>
#include <cmath>

namespace anyphys::restitution {

/// The separating normal speed to leave with so that the pair passes back through the level of
/// first contact at e times the speed it met there, as a bounce at the instant of contact would.
/// `closing` is the normal closing speed at the step's start (before the step's gravity), `depth`
/// the overlap found there, `g` the relative acceleration pulling the pair together along the
/// normal (gravity's share; < 0 pulls it apart) and `h` the step. A negative depth is a gap the
/// step would close, bounced now as if touching (Bullet's speculative points).
///
/// Semi-implicit Euler moves each step with the velocity after that step's gravity: a discrete
/// flight at speed v keeps the energy of an exact one at speed v + g h / 2 (a fall from rest has
/// v^2 + v g h = 2 g H after every step, up to the sampled g^2 h^2 / 4). So the pair met at
/// v_i^2 = (closing + g h / 2)^2 - 2 g depth, and leaving at u from the depth it passes the contact
/// level at (u + g h / 2)^2 - 2 g depth. Setting that to (e v_i)^2 gives the speed below; at depth 0
/// it is e closing - (1 - e) g h / 2, the rule Box2D's backend applies at contact.
///
/// Engines that bounce at e closing from the depth lose that depth from the rise: a ball with
/// e = 0.2 landing at 3.9 m/s at 60 Hz, found 6.5 cm deep, rose 3.1 cm from there and never left
/// its resting height.
///
/// The depth counted is at most the closing speed's one step of travel either way: an overlap
/// deeper than that was there before the step that brought the pair together (a body created
/// overlapping), and is the engine's push-out's to resolve, not the bounce's.
inline double reboundFromDepth(double e, double closing, double depth, double g, double h) {
    const double travel = std::max(closing, 0.0) * h;
    const double fall = std::clamp(depth, -travel, travel);
    const double met = closing + 0.5 * g * h;
    const double metSquared = std::max(met * met - 2.0 * g * fall, 0.0);
    const double leave = std::sqrt(std::max(e * e * metSquared + 2.0 * g * fall, 0.0)) - 0.5 * g * h;
    return std::max(leave, 0.0);
}

/// Whether a body fell freely over the last step h: it gained at least half a step of its gravity
/// (`gained`: its velocity change along its gravity, which has squared length `fallSquared`). A
/// body resting on something gains none, and its gravity must not count in a bounce's relative
/// acceleration: a ball bouncing on a box resting on the ground is not aimed as if the box fell.
inline bool fellFreely(double gained, double fallSquared, double h) { return !(gained < 0.5 * fallSquared * h); }

/// A body's fellFreely verdict on its last step, from its linear velocity at each step's start, in
/// the engine's vector type; every backend's bodies keep one. The world notes its bodies only while
/// some material bounces. With no velocity to compare (the body's first note, or the world noted no
/// one at the step before) the body counts as falling. A body that slept compares against its
/// velocity before it slept: a box woken by a ball landing on it rested, and does not fall.
template <class Velocity>
class FreeFallWatch {
public:
    explicit FreeFallWatch(const Velocity& atRest) : velocity_(atRest) {}
    /// At a step's start: the body's `velocity`, its `gravity` and the last step's `h`; whether the
    /// world noted its bodies at the step before (`notedLastStep`); `dot` is the engine's dot product.
    template <class Dot>
    void note(bool notedLastStep, const Velocity& velocity, const Velocity& gravity, double h, Dot dot) {
        fell_ = !(noted_ && notedLastStep) || fellFreely(dot(velocity - velocity_, gravity), dot(gravity, gravity), h);
        velocity_ = velocity;
        noted_ = true;
    }
    bool fellLastStep() const { return fell_; }
    /// The velocity noted at the last step's start.
    const Velocity& stepStartVelocity() const { return velocity_; }

private:
    Velocity velocity_;
    bool noted_ = false;  // velocity_ holds a step start's
    bool fell_ = true;
};

}  // namespace anyphys::restitution
