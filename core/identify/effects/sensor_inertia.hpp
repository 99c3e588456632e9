// sensor_inertia: the measured force includes a mass times the slider's acceleration.
#pragma once

#include "effect.hpp"

namespace stickslip::identify {

// F_measured = F + m_s a, with a the acceleration of the body the force sensor carries
// (the slider in the rig; the driven side, g'', in the prescribed set-up).
struct SensorInertia {
    double mass_kg = 0.0;  // m_s, mass between the contact and the sensing element [kg]

    double measured(double force_N, double accel_mps2) const { return force_N + mass_kg * accel_mps2; }

    static EffectInfo info() {
        return {"sensor_inertia",
                "A force sensor sits behind some mass (fixture, part of the slider), so it reads the "
                "friction force plus that mass times the acceleration. At higher frequencies and "
                "amplitudes this inertial part grows with omega^2 A and shifts the measured force in "
                "phase with the acceleration.",
                "Residual proportional to the acceleration of the sensed body: strong correlation "
                "with dV/dt (and the slider acceleration), largest at reversals of the drive.",
                {{"mass_kg", "kg", 0.0, -50.0, 50.0, false}},
                {"accel", "dVdt"},
                {true, true}};
    }
};

}  // namespace stickslip::identify
