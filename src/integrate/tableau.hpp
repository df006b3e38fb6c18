// Method coefficients, as data.
#pragma once

#include <string>
#include <vector>

namespace beltsim {

struct ExplicitTableau {
  std::vector<std::vector<double>> a;  // strictly lower triangular
  std::vector<double> b, b_hat, c;     // propagated weights, embedded weights, nodes
};
const ExplicitTableau& fehlberg45();

// Singly diagonally implicit RK with an explicit first stage (ESDIRK), stiffly accurate:
//   Y_1 = y,  Y_i = y + h·Σ_{j<i} a_ij·F(t + c_j·h, Y_j) + h·γ·F(t + c_i·h, Y_i),  y1 = Y_s
struct EsdirkTableau {
  std::string name;
  int order = 0, embedded_order = 0;
  int stages = 0;
  double gamma = 0;
  std::vector<std::vector<double>> a;  // full rows, a[i][i] = γ for i >= 1
  std::vector<double> b, b_hat, c;
  // the interior stage values are solutions good enough for the dense output (one_step.cpp):
  // trbdf2's is the trapezoidal rule's own second-order solution at 2γ. esdirk32's are not, at the
  // steps it takes on the belt: through them its samples of the paper's dry drive at rtol 1e-3
  // were 8.1e-2 off in the span tensions, against 2.9e-2 with the Hermite cubic (commit message)
  bool interior_stages = false;
};
const EsdirkTableau& esdirk32();
const EsdirkTableau& trbdf2();

// Rosenbrock method in the form of Hairer & Wanner (IV.7.4):
//   (I - h·γ·J)·k_i = h·F(t + α_i·h, y + Σ_j α_ij·k_j) + h·J·Σ_j γ_ij·k_j + γ_i·h²·F_t
//   y1 = y + Σ b_i·k_i,   ŷ1 = y + Σ b̂_i·k_i
// and the transformed coefficients (u_i = Σ_j γ_ij·k_j, so no product with J is needed):
//   (I/(h·γ) - J)·u_i = F(t + α_i·h, y + Σ_j a_ij·u_j) + Σ_j (c_ij/h)·u_j + γ_i·h·F_t
//   a = α·Γ^-1,  c = diag(1/γ) - Γ^-1,  m = bᵀ·Γ^-1,  e = (b - b̂)ᵀ·Γ^-1
struct RosenbrockTableau {
  int stages = 0;
  double gamma = 0;
  std::vector<std::vector<double>> alpha, Gamma;  // Γ lower triangular, diagonal γ
  std::vector<double> b, b_hat;
  // derived
  std::vector<std::vector<double>> a, c;
  std::vector<double> m, e, alpha_sum, gamma_sum;
  void derive();
};
const RosenbrockTableau& ros34pw2();

}  // namespace beltsim
