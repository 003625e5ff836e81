// A small multilayer perceptron engine: any layer widths, one activation per layer, a scalar
// double-precision reference path (forward pass, back-propagation, Jacobian) for training and
// testing, and a single-precision SIMD batch path (MlpBatch, Highway, structure of arrays).
//
// Notation of Satilmis et al. 2016 (§III-B): layer k = 0 (input) .. L (output) has n_k neurons;
// w^k_{j_k j_(k-1)} is the weight from neuron j_(k-1) of layer k-1 to neuron j_k of layer k and
// w^k_{j_k 0} the bias weight (the constant-1 neuron of layer k-1). A layer's output is eq. 5:
//   o^k_j = f_k( sum_i w^k_{j i} o^(k-1)_i + w^k_{j 0} ),   o^0 = the input vector,
// and the network Psi(V) = o^L (eq. 6 for L = 2). The paper uses f(x) = 1/(1 + x^2) on every
// layer; here each layer k has its own activation f_k.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace skylight::nn {

enum class Activation {
  identity,  // f(x) = x
  satilmis,  // f(x) = 1 / (1 + x^2), Satilmis et al. 2016 eq. 5 (a radial basis function)
  pietras,   // f(x) = 1 / (1 + 2^(2x)), Pietras (GPU MLP for Nishita's sky)
  tanh,      // f(x) = tanh x
  sigmoid,   // f(x) = 1 / (1 + e^-x)
  relu,      // f(x) = max(0, x)
  softplus,  // f(x) = ln(1 + e^x)
};
std::string_view to_string(Activation a);
std::optional<Activation> parse_activation(std::string_view name);

// f(x).
double activate(Activation a, double x);
// f'(x), given x and y = f(x) (most derivatives are cheapest from y).
double activation_derivative(Activation a, double x, double y);

// Widths n_0 (inputs) .. n_L (outputs) and the activation f_k of each layer k = 1..L.
// Parameter vector order: for k = 1..L, the weights W^k (n_k x n_(k-1), row-major: row j holds
// w^k_{j 1..n_(k-1)}), then the biases w^k_{j 0} (n_k values).
struct MlpLayout {
  std::vector<int> widths;
  std::vector<Activation> activations;  // activations[k - 1] = f_k

  // n_in - hidden... - n_out, hidden layers with `hidden`, the output layer with `output`.
  static MlpLayout make(int inputs, const std::vector<int>& hidden_widths, int outputs,
                        Activation hidden, Activation output);

  int layers() const { return static_cast<int>(widths.size()) - 1; }  // L
  int inputs() const { return widths.front(); }
  int outputs() const { return widths.back(); }
  int max_width() const;
  std::size_t parameter_count() const;
  std::size_t weight_offset(int k) const;  // first w^k_{1 1}
  std::size_t bias_offset(int k) const;    // first w^k_{1 0}
  // Throws InvalidArgument unless L >= 1, every width >= 1 and one activation per layer.
  void validate() const;
  // e.g. "6-12-3 satilmis/satilmis" (hidden/output activation).
  std::string describe() const;
};

// The largest weight magnitude a weights file may hold (the loaders refuse larger ones, naming
// the element): trained networks stay far below it (data/nn/: at most 531), and with it every
// weight is finite in single precision (the GPU's type and the GLSL export's) and so are the
// products of a layer.
inline constexpr double kMaxWeightMagnitude = 1e6;
// InvalidArgument "<where>: field '<name>' holds <value> (element <i>), beyond ±1e+06 ..." for the
// first weight beyond kMaxWeightMagnitude.
void check_weight_magnitudes(std::span<const double> weights, const std::string& where,
                             const std::string& name);

class Mlp {
 public:
  Mlp() = default;
  explicit Mlp(MlpLayout layout);  // all parameters 0
  Mlp(MlpLayout layout, std::vector<double> parameters);

  const MlpLayout& layout() const { return layout_; }
  std::span<const double> parameters() const { return params_; }
  std::span<double> parameters() { return params_; }

  // Reference forward pass (eq. 5 layer by layer), double precision. in.size() == n_0,
  // out.size() == n_L.
  void forward(std::span<const double> in, std::span<double> out) const;
  std::vector<double> operator()(std::span<const double> in) const;

 private:
  MlpLayout layout_;
  std::vector<double> params_;
};

// Every layer's pre-activations and outputs of one forward pass, kept for back-propagation.
class MlpWorkspace {
 public:
  explicit MlpWorkspace(const MlpLayout& layout);
  std::span<const double> output() const { return layer_output(static_cast<int>(o_.size()) - 1); }
  std::span<const double> layer_output(int k) const { return o_[k]; }  // o^k, o^0 = input

 private:
  friend void forward(const Mlp&, std::span<const double>, MlpWorkspace&);
  friend void backward(const Mlp&, MlpWorkspace&, std::span<const double>, std::span<double>);
  friend void jacobian(const Mlp&, MlpWorkspace&, std::span<double>);
  std::vector<std::vector<double>> a_;      // a^k: pre-activations, k = 1..L (a_[0] unused)
  std::vector<std::vector<double>> o_;      // o^k, k = 0..L
  std::vector<std::vector<double>> delta_;  // dE/da^k during back-propagation
};

// Forward pass keeping a^k and o^k in ws (ws.output() is Psi(in)).
void forward(const Mlp& net, std::span<const double> in, MlpWorkspace& ws);
// Back-propagation of the last forward pass in ws: grad += d(sum_c g_c Psi_c)/d(parameters),
// grad.size() == parameter_count(). With g = dE/dPsi this is the gradient of E (eq. 9).
void backward(const Mlp& net, MlpWorkspace& ws, std::span<const double> g, std::span<double> grad);
// The Jacobian dPsi_c/d(parameters) of the last forward pass in ws: n_L rows of
// parameter_count() values, row-major, overwritten.
void jacobian(const Mlp& net, MlpWorkspace& ws, std::span<double> jac);

// ---- batch path ---------------------------------------------------------------------------------

// A single-precision copy of a network for the SIMD batch path (weights rounded once).
// Error against Mlp::forward: see kBatchRelativeTolerance in mlp_test.cpp.
class MlpBatch {
 public:
  explicit MlpBatch(const Mlp& net);
  const MlpLayout& layout() const { return layout_; }
  // outputs[c][i] = Psi(inputs[0][i], .., inputs[n_0 - 1][i])_c for i < n: structure of arrays,
  // inputs.size() == n_0 pointers to n floats each, outputs.size() == n_L. Calling thread only.
  void forward(std::span<const float* const> inputs, std::span<float* const> outputs,
               std::size_t n) const;

 private:
  MlpLayout layout_;
  std::vector<float> params_;
};

}  // namespace skylight::nn
