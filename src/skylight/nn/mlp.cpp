#include "skylight/nn/mlp.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "skylight/core/error.h"
#include "skylight/nn/detail/mlp_kernel.h"

namespace skylight::nn {

void check_weight_magnitudes(std::span<const double> weights, const std::string& where,
                             const std::string& name) {
  for (std::size_t i = 0; i < weights.size(); ++i)
    if (!(std::abs(weights[i]) <= kMaxWeightMagnitude))
      throw InvalidArgument(fmt::format(
          "{}: field '{}' holds {} (element {}), beyond +-{:g}, the largest weight a network file "
          "may hold (finite in single precision on the GPU; trained networks stay far below)",
          where, name, weights[i], i + 1, kMaxWeightMagnitude));
}

namespace {

struct ActivationName {
  Activation a;
  std::string_view name;
};
constexpr ActivationName kActivationNames[] = {
    {Activation::identity, "identity"}, {Activation::satilmis, "satilmis"},
    {Activation::pietras, "pietras"},   {Activation::tanh, "tanh"},
    {Activation::sigmoid, "sigmoid"},   {Activation::relu, "relu"},
    {Activation::softplus, "softplus"},
};

double sigmoid(double x) {
  // Both branches avoid exp overflow.
  if (x >= 0.0) return 1.0 / (1.0 + std::exp(-x));
  const double e = std::exp(x);
  return e / (1.0 + e);
}

}  // namespace

std::string_view to_string(Activation a) {
  for (const auto& n : kActivationNames) {
    if (n.a == a) return n.name;
  }
  return "?";
}

std::optional<Activation> parse_activation(std::string_view name) {
  for (const auto& n : kActivationNames) {
    if (n.name == name) return n.a;
  }
  return std::nullopt;
}

double activate(Activation a, double x) {
  switch (a) {
    case Activation::identity:
      return x;
    case Activation::satilmis:
      return 1.0 / (1.0 + x * x);
    case Activation::pietras:
      // 1 / (1 + 2^(2x)) = sigmoid(-2 ln2 x)
      return sigmoid(-2.0 * std::numbers::ln2 * x);
    case Activation::tanh:
      return std::tanh(x);
    case Activation::sigmoid:
      return sigmoid(x);
    case Activation::relu:
      return x > 0.0 ? x : 0.0;
    case Activation::softplus:
      return std::max(x, 0.0) + std::log1p(std::exp(-std::abs(x)));
  }
  return x;
}

double activation_derivative(Activation a, double x, double y) {
  switch (a) {
    case Activation::identity:
      return 1.0;
    case Activation::satilmis:
      return -2.0 * x * y * y;  // d/dx (1 + x^2)^-1 = -2x (1 + x^2)^-2
    case Activation::pietras:
      return -2.0 * std::numbers::ln2 * y * (1.0 - y);
    case Activation::tanh:
      return 1.0 - y * y;
    case Activation::sigmoid:
      return y * (1.0 - y);
    case Activation::relu:
      return x > 0.0 ? 1.0 : 0.0;
    case Activation::softplus:
      return sigmoid(x);
  }
  return 1.0;
}

// ---- MlpLayout
// -----------------------------------------------------------------------------------

MlpLayout MlpLayout::make(int inputs, const std::vector<int>& hidden_widths, int outputs,
                          Activation hidden, Activation output) {
  MlpLayout l;
  l.widths.push_back(inputs);
  for (int w : hidden_widths) {
    l.widths.push_back(w);
    l.activations.push_back(hidden);
  }
  l.widths.push_back(outputs);
  l.activations.push_back(output);
  l.validate();
  return l;
}

int MlpLayout::max_width() const {
  return widths.empty() ? 0 : *std::max_element(widths.begin(), widths.end());
}

std::size_t MlpLayout::parameter_count() const {
  std::size_t n = 0;
  for (int k = 1; k <= layers(); ++k) {
    n += static_cast<std::size_t>(widths[k]) * static_cast<std::size_t>(widths[k - 1] + 1);
  }
  return n;
}

std::size_t MlpLayout::weight_offset(int k) const {
  std::size_t n = 0;
  for (int i = 1; i < k; ++i) {
    n += static_cast<std::size_t>(widths[i]) * static_cast<std::size_t>(widths[i - 1] + 1);
  }
  return n;
}

std::size_t MlpLayout::bias_offset(int k) const {
  return weight_offset(k) + static_cast<std::size_t>(widths[k]) * widths[k - 1];
}

void MlpLayout::validate() const {
  if (widths.size() < 2) throw InvalidArgument("MLP layout: needs an input and an output layer");
  for (int w : widths) {
    if (w < 1 || w > detail::kMaxBatchWidth) {
      throw InvalidArgument("MLP layout: width " + std::to_string(w) + " is outside [1, " +
                            std::to_string(detail::kMaxBatchWidth) + "]");
    }
  }
  if (static_cast<int>(activations.size()) != layers()) {
    throw InvalidArgument("MLP layout: " + std::to_string(activations.size()) +
                          " activations for " + std::to_string(layers()) + " layers");
  }
}

std::string MlpLayout::describe() const {
  std::ostringstream s;
  for (std::size_t i = 0; i < widths.size(); ++i) s << (i ? "-" : "") << widths[i];
  s << ' ';
  if (layers() > 1) s << to_string(activations.front()) << '/';
  s << to_string(activations.back());
  return s.str();
}

// ---- Mlp
// -----------------------------------------------------------------------------------------

Mlp::Mlp(MlpLayout layout) : layout_(std::move(layout)) {
  layout_.validate();
  params_.assign(layout_.parameter_count(), 0.0);
}

Mlp::Mlp(MlpLayout layout, std::vector<double> parameters)
    : layout_(std::move(layout)), params_(std::move(parameters)) {
  layout_.validate();
  if (params_.size() != layout_.parameter_count()) {
    throw InvalidArgument("MLP: " + std::to_string(params_.size()) + " parameters for layout " +
                          layout_.describe() + " (needs " +
                          std::to_string(layout_.parameter_count()) + ")");
  }
}

void Mlp::forward(std::span<const double> in, std::span<double> out) const {
  SKYLIGHT_CHECK(static_cast<int>(in.size()) == layout_.inputs(), "Mlp::forward: input size");
  SKYLIGHT_CHECK(static_cast<int>(out.size()) == layout_.outputs(), "Mlp::forward: output size");
  std::vector<double> prev(in.begin(), in.end()), next;
  for (int k = 1; k <= layout_.layers(); ++k) {
    const int n_in = layout_.widths[k - 1], n_out = layout_.widths[k];
    const double* W = params_.data() + layout_.weight_offset(k);
    const double* b = params_.data() + layout_.bias_offset(k);
    next.assign(n_out, 0.0);
    for (int j = 0; j < n_out; ++j) {
      double a = b[j];  // eq. 5: sum_i w_ji o_i + w_j0
      for (int i = 0; i < n_in; ++i) a += W[j * n_in + i] * prev[i];
      next[j] = activate(layout_.activations[k - 1], a);
    }
    prev.swap(next);
  }
  std::copy(prev.begin(), prev.end(), out.begin());
}

std::vector<double> Mlp::operator()(std::span<const double> in) const {
  std::vector<double> out(layout_.outputs());
  forward(in, out);
  return out;
}

// ---- forward / backward with workspace
// -----------------------------------------------------------

MlpWorkspace::MlpWorkspace(const MlpLayout& layout) {
  const int L = layout.layers();
  a_.resize(L + 1);
  o_.resize(L + 1);
  delta_.resize(L + 1);
  for (int k = 0; k <= L; ++k) {
    a_[k].assign(layout.widths[k], 0.0);
    o_[k].assign(layout.widths[k], 0.0);
    delta_[k].assign(layout.widths[k], 0.0);
  }
}

void forward(const Mlp& net, std::span<const double> in, MlpWorkspace& ws) {
  const MlpLayout& l = net.layout();
  SKYLIGHT_CHECK(static_cast<int>(in.size()) == l.inputs(), "forward: input size");
  const double* p = net.parameters().data();
  std::copy(in.begin(), in.end(), ws.o_[0].begin());
  for (int k = 1; k <= l.layers(); ++k) {
    const int n_in = l.widths[k - 1], n_out = l.widths[k];
    const double* W = p + l.weight_offset(k);
    const double* b = p + l.bias_offset(k);
    const double* prev = ws.o_[k - 1].data();
    const Activation f = l.activations[k - 1];
    for (int j = 0; j < n_out; ++j) {
      double a = b[j];
      const double* w = W + static_cast<std::size_t>(j) * n_in;
      for (int i = 0; i < n_in; ++i) a += w[i] * prev[i];
      ws.a_[k][j] = a;
      ws.o_[k][j] = activate(f, a);
    }
  }
}

void backward(const Mlp& net, MlpWorkspace& ws, std::span<const double> g, std::span<double> grad) {
  const MlpLayout& l = net.layout();
  const int L = l.layers();
  SKYLIGHT_CHECK(static_cast<int>(g.size()) == l.outputs(), "backward: output gradient size");
  SKYLIGHT_CHECK(grad.size() == l.parameter_count(), "backward: gradient size");
  const double* p = net.parameters().data();
  // delta^L_j = g_j f_L'(a^L_j)
  for (int j = 0; j < l.widths[L]; ++j) {
    ws.delta_[L][j] = g[j] * activation_derivative(l.activations[L - 1], ws.a_[L][j], ws.o_[L][j]);
  }
  for (int k = L; k >= 1; --k) {
    const int n_in = l.widths[k - 1], n_out = l.widths[k];
    const double* W = p + l.weight_offset(k);
    double* gW = grad.data() + l.weight_offset(k);
    double* gb = grad.data() + l.bias_offset(k);
    const double* prev = ws.o_[k - 1].data();
    const double* delta = ws.delta_[k].data();
    for (int j = 0; j < n_out; ++j) {
      const double dj = delta[j];
      if (dj == 0.0) continue;
      double* gw = gW + static_cast<std::size_t>(j) * n_in;
      for (int i = 0; i < n_in; ++i) gw[i] += dj * prev[i];
      gb[j] += dj;
    }
    if (k == 1) break;
    // delta^(k-1)_i = f_(k-1)'(a^(k-1)_i) sum_j w^k_ji delta^k_j
    double* dprev = ws.delta_[k - 1].data();
    std::fill(dprev, dprev + n_in, 0.0);
    for (int j = 0; j < n_out; ++j) {
      const double dj = delta[j];
      if (dj == 0.0) continue;
      const double* w = W + static_cast<std::size_t>(j) * n_in;
      for (int i = 0; i < n_in; ++i) dprev[i] += w[i] * dj;
    }
    const Activation f = l.activations[k - 2];
    for (int i = 0; i < n_in; ++i) {
      dprev[i] *= activation_derivative(f, ws.a_[k - 1][i], ws.o_[k - 1][i]);
    }
  }
}

void jacobian(const Mlp& net, MlpWorkspace& ws, std::span<double> jac) {
  const MlpLayout& l = net.layout();
  const std::size_t P = l.parameter_count();
  const int n_out = l.outputs();
  SKYLIGHT_CHECK(jac.size() == P * n_out, "jacobian: size");
  std::fill(jac.begin(), jac.end(), 0.0);
  std::vector<double> g(n_out, 0.0);
  for (int c = 0; c < n_out; ++c) {
    g[c] = 1.0;
    backward(net, ws, g, jac.subspan(c * P, P));
    g[c] = 0.0;
  }
}

// ---- MlpBatch
// ------------------------------------------------------------------------------------

MlpBatch::MlpBatch(const Mlp& net) : layout_(net.layout()) {
  params_.resize(net.parameters().size());
  std::transform(net.parameters().begin(), net.parameters().end(), params_.begin(),
                 [](double v) { return static_cast<float>(v); });
}

void MlpBatch::forward(std::span<const float* const> inputs, std::span<float* const> outputs,
                       std::size_t n) const {
  SKYLIGHT_CHECK(static_cast<int>(inputs.size()) == layout_.inputs(), "MlpBatch: input count");
  SKYLIGHT_CHECK(static_cast<int>(outputs.size()) == layout_.outputs(), "MlpBatch: output count");
  std::vector<detail::BatchLayer> layers(layout_.layers());
  for (int k = 1; k <= layout_.layers(); ++k) {
    layers[k - 1] = {layout_.widths[k - 1], layout_.widths[k], layout_.activations[k - 1],
                     params_.data() + layout_.weight_offset(k),
                     params_.data() + layout_.bias_offset(k)};
  }
  detail::mlp_batch(layers.data(), layout_.layers(), inputs.data(), outputs.data(), n);
}

}  // namespace skylight::nn
