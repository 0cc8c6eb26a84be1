// The stride-to-stride response of the body controller, in closed form: what relative
// gains mean. The controller acts once per stride, so each PD channel is a linear map
// from one touchdown to the next, and its two poles (multipliers) say how fast an error
// dies out per stride. These functions turn poles into gains and back, for one channel
// and for the legged robot's lateral loop (roll PD + banking), on a stride of known
// flight and stance time. Units: relative gains are per unit mass (x, y, z) or per unit
// inertia about the body axis (roll, pitch, yaw): kp [1/s], kd [-].
#pragma once

#include <array>
#include <complex>

#include <Eigen/Core>

namespace pronk::scene {

/// One stride at the gait's periodic orbit [s].
struct StrideTiming {
  double flight = 0.0;  ///< takeoff to touchdown [s]
  double stance = 0.0;  ///< touchdown to takeoff; 0 for impulses [s]
  double period() const { return flight + stance; }
};

/// Flight time of the seed's hop law: takeoff at sqrt(2 g h) from the leg length, back
/// to it [s]; with the pulse-aware law (stance > 0), the takeoff speed v1 with
/// (v1 - v0) T / 2 + v1^2 / (2 g) = h for the touchdown speed v0 = sqrt(2 g h).
double hop_flight_time(double gravity, double hop_height, double stance, bool pulse_aware);

/// Poles of one PD channel on impulses, relative gains kp [1/s], kd [-]. The impulse
/// (a constant force over the stance) changes the rate error by -kp e - kd v; the error
/// moves by the rate over the stride. The map of (e, v) from touchdown to touchdown:
///   v' = (1 - kd) v - kp e,   e' = e + T v + (T - Ts/2)(v' - v)
/// with T the stride period and Ts the stance; its poles satisfy
///   z1 z2 = 1 - kd + kp Ts / 2,   (1 - z1)(1 - z2) = kp T.
std::array<std::complex<double>, 2> pd_channel_poles(double kp, double kd, const StrideTiming& t);

/// The inverse: the relative gains whose poles are z1, z2 (a conjugate pair or two reals):
///   kp = (1 - z1)(1 - z2) / T,   kd = 1 - z1 z2 + kp Ts / 2.
void pd_channel_gains(std::complex<double> z1, std::complex<double> z2, const StrideTiming& t,
                      double* kp, double* kd);

/// One position channel with integral action, as the full model runs it: the PD above on
/// the position the controller perceives, e + I, where the trim I (a position offset seen)
/// grows by g e at each touchdown before the plan. State (e, v, I) at touchdown:
///   I' = I + g e,   v' = (1 - kd) v - kp (e + I'),   e' = e + T v + (T - Ts/2)(v' - v).
/// Relative gains kp [1/s], kd [-]; g is the trim gain per stride [-].
struct PositionLoop {
  double kp = 0.0, kd = 0.0, trim = 0.0;
};
Eigen::Matrix3d position_stride_map(const PositionLoop& loop, const StrideTiming& t);

/// The gains whose map above has the three real poles z1..z3 (each in (0, 1)), in closed
/// form: with q = z - 1 and a = T - Ts/2 the characteristic polynomial in w = z - 1 is
///   w^3 + (kd + a kp (1 + g)) w^2 + (T kp (1 + g) + a kp g) w + T kp g,
/// matched to (w - q1)(w - q2)(w - q3).
PositionLoop place_position_poles(const std::array<double, 3>& poles, const StrideTiming& t);

/// The poles of a continuous response of natural frequency omega [rad/s] and damping
/// ratio zeta [-] sampled once per stride: z = exp(T s), s = -zeta omega +- omega
/// sqrt(zeta^2 - 1) (a complex pair below zeta 1, two reals above).
std::array<std::complex<double>, 2> response_poles(double omega, double zeta, double period);

/// The legged robot's lateral loop: legs cannot push sideways, so the roll PD tilts the
/// legs' vertical impulse (m g T per stride) and banking asks for a roll from the
/// lateral error. State at touchdown (u, w, phi, W) = (e_y / (g T^2), v_y / (g T), roll,
/// roll rate x T); the roll request is phi_d = beta_p u + beta_d w, the roll channel's
/// rate change k (phi_d - phi) - b W (k = kp_roll T, b = kd_roll, relative). The map of
/// one stride with a constant moment and a constant push over the stance fraction
/// sigma = Ts / T (small angles).
struct LateralLoop {
  double kp_roll = 0.0;  ///< relative roll gain [1/s]
  double kd_roll = 0.0;  ///< relative roll rate gain [-]
  double bank_kp = 0.0;  ///< desired roll per lateral error [rad/m]
  double bank_kd = 0.0;  ///< desired roll per lateral velocity error [rad s/m]
};
Eigen::Matrix4d lateral_stride_map(const LateralLoop& loop, const StrideTiming& t, double gravity);

/// The lateral loop whose four poles are `poles` (real, in (-1, 1)): pole placement on
/// the map above (Ackermann's formula; the roll gains and the bank gains together).
LateralLoop place_lateral_poles(const std::array<double, 4>& poles, const StrideTiming& t,
                                double gravity);

/// Bank gains for given roll gains: the (bank_kp, bank_kd) >= 0 that minimise the
/// spectral radius of the lateral map (a refined grid search; deterministic).
LateralLoop best_bank_gains(double kp_roll, double kd_roll, const StrideTiming& t, double gravity);

/// Largest |eigenvalue| of a square matrix.
double spectral_radius(const Eigen::Matrix4d& a);

}  // namespace pronk::scene
