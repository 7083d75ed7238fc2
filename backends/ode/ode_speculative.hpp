#pragma once
// Speculative contacts for ODE: contacts made a step before the shapes meet.
//
// ODE's colliders report a pair only once its shapes overlap, so a body closing on another is
// first seen up to a step's travel inside it, and the contact row's ERP target pushes that overlap
// out as a velocity. Nothing takes that velocity back where nothing pulls the bodies together: a
// box on ice sliding into a wall with no restitution bounced back at up to 15 % of its speed, and
// one pushed by a kinematic paddle left 3 to 8 % faster than the paddle. A pair still apart that
// can close within the step is collided again with one shape grown by that approach (NearProbe);
// each point whose own closing speed covers its gap becomes a contact whose row lets the pair
// close the gap and no more (ODE's motionN: a negative target speed, OdeWorld::meetingOverlap),
// so the bodies meet at the step's end, and nothing is pushed out.
#include <ode/ode.h>

#include "anyphys/defs.hpp"
#include "ode_near_pairs.hpp"

namespace anyphys::ode {

class OdeBody;
class OdeShape;

/// Of linearSlop: the least a pair must close by in a step to get speculative contacts (0.5 mm at
/// the default, 3 cm/s at 60 Hz). Closing by less, it overlaps the step after by less than ODE's
/// surface layer (0.2 linearSlop), which ERP leaves alone: resting pairs keep ODE's contacts.
inline constexpr double kLeastApproach = 0.1;
/// Of a dynamic body's core extent: the most a pair may close by in a step to get speculative
/// contacts. Faster is continuous collision's, which starts at half the core.
inline constexpr double kMostApproach = 0.5;

/// How far the shapes `a` and `b` can close on each other over a step of `h`: their bodies'
/// relative speed plus each body's spin times its shape's reach. 0 for two bodies at rest.
double stepApproach(const OdeShape& a, const OdeShape& b, double h);

/// What the look ahead of one pair knows of the step.
struct StepAhead {
    bool touching = false;     ///< ODE found the pair touching (then no passing-beside test)
    Vec3 fall = Vec3::Zero();  ///< the velocity gravity adds over the step, a's less b's
    double approach = 0.0;     ///< how far the pair can close over the step (stepApproach)
    double slop = 0.0;         ///< the world's linearSlop
    double h = 0.0;            ///< the ODE step
};

/// Contacts for `a` and `b`, apart now, that the step brings together: from the pair collided
/// with `a` grown by `approach` + `slop`, each point taken back to `a`'s true surface, its depth
/// measured there (negative: the gap), and kept if it overlaps or its closing speed along the
/// normal covers its gap (less kLeastApproach of `slop`), gravity's `fall` counted (ODE moves the
/// bodies with the step's last velocity). Normals point into `a` (ODE's convention). Unless
/// `touching`, none unless `a`, moved over the step by the pair's relative motion, comes within
/// `slop` of `b`: a box passing beside another meets the grown one's face. `probe` holds scratch
/// geoms.
int speculativeContacts(NearProbe& probe, const OdeShape& a, const OdeShape& b, const StepAhead& step, dContact* out, int most);

}  // namespace anyphys::ode
