#pragma once
//! RODAS4's coefficients (internal to the Model 2 integrators).
//!
//! The 6-stage, order 4(3), L-stable and stiffly accurate Rosenbrock method of E. Hairer and
//! G. Wanner, "Solving Ordinary Differential Equations II", 2nd ed., Springer 1996, Sec. VI.4
//! (coefficients of their code rodas.f, METH = 1; Boost.Odeint's rosenbrock4 uses the same
//! set). Written in the "g" form of rodas.f:
//!   (I/(gamma h) - J) g_i = f(t + C_i h, y + sum_j a_ij g_j) + sum_j (c_ij / h) g_j + D_i h df/dt,
//!   y1 = y + sum_j a_5j g_j + g_5 + g_6, error estimate = g_6 (stages 5 and 6 at t + h).
//! The autonomous integrator (model2_integrator.cpp) needs neither C_i nor D_i.
namespace stengmc::rodas4 {

inline constexpr double GAMMA = 0.25;
inline constexpr double A21 = 1.544;
inline constexpr double A31 = 0.9466785280815826, A32 = 0.2557011698983284;
inline constexpr double A41 = 3.314825187068521, A42 = 2.896124015972201, A43 = 0.9986419139977817;
inline constexpr double A51 = 1.221224509226641, A52 = 6.019134481288629, A53 = 12.53708332932087,
                        A54 = -0.6878860361058950;
inline constexpr double C21 = -5.6688;
inline constexpr double C31 = -2.430093356833875, C32 = -0.2063599157091915;
inline constexpr double C41 = -0.1073529058151375, C42 = -9.594562251023355, C43 = -20.47028614809616;
inline constexpr double C51 = 7.496443313967647, C52 = -10.24680431464352, C53 = -33.99990352819905,
                        C54 = 11.70890893206160;
inline constexpr double C61 = 8.083246795921522, C62 = -7.981132988064893, C63 = -31.52159432874371,
                        C64 = 16.31930543123136, C65 = -6.058818238834054;
//! Stage times t + STAGE_k h of stages 2..4 (stages 5 and 6 are at t + h): the row sums of
//! alpha = a Gamma (rodas.f C2..C4).
inline constexpr double STAGE2 = 0.386, STAGE3 = 0.21, STAGE4 = 0.63;
//! D_i = gamma_i, the row sums of Gamma (rodas.f D1..D4; D5 = D6 = 0). D4 is negative:
//! the row sums of Gamma = (I/gamma - c)^-1 give -0.0362 (Boost.Odeint's rosenbrock4 prints
//! +0.0362, which only matters for non-autonomous systems).
inline constexpr double D1 = 0.25, D2 = -0.1043, D3 = 0.1035, D4 = -0.0362;

}  // namespace stengmc::rodas4
