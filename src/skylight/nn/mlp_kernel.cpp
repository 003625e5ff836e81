// Highway dynamic dispatch: this file is compiled once per SIMD target (foreach_target.h).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skylight/nn/mlp_kernel.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
//
#include <hwy/contrib/math/math-inl.h>
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "skylight/nn/detail/mlp_kernel.h"

// Layout of the per-vector scratch: activation i of the current layer for lane l is at
// buf[i * N + l] (N = lanes of the target), so each neuron is one aligned vector load. A layer
// computes four output neurons at a time: one load of each input vector feeds four FMAs whose
// weight operand is a broadcast from memory, and the four accumulators hide the FMA latency.

HWY_BEFORE_NAMESPACE();
namespace skylight::nn {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using detail::BatchLayer;

// f(x) = 1/(1 + x^2) (Satilmis et al. 2016 eq. 5), an exact (correctly rounded) division: the
// same result on every target, and on the AVX-512 machine measured faster than the reciprocal
// estimate + one Newton step (6-12-3 sky kernel, 1024 x 512 hemisphere: 0.67 vs 0.74 ms; the bare
// estimate, 14 bits, 0.61 ms). CPUs with a slow vector divider may prefer the estimate.
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Satilmis(D d, V x) {
  return hn::Div(hn::Set(d, 1.0f), hn::MulAdd(x, x, hn::Set(d, 1.0f)));
}

template <class D, class V = hn::Vec<D>>
HWY_INLINE V Sigmoid(D d, V x) {
  // 1/(1 + e^-x). hn::Exp is specified for arguments <= 88 only (beyond, its result is not inf
  // but wrong), so -x is clamped there: e^88 = 1.7e38 gives 6e-39, i.e. 0 in float as it should.
  const V e = hn::Exp(d, hn::Min(hn::Neg(x), hn::Set(d, 88.0f)));
  return hn::Div(hn::Set(d, 1.0f), hn::Add(hn::Set(d, 1.0f), e));
}

template <Activation F, class D, class V = hn::Vec<D>>
HWY_INLINE V Activate(D d, V x) {
  if constexpr (F == Activation::identity) {
    return x;
  } else if constexpr (F == Activation::satilmis) {
    return Satilmis(d, x);
  } else if constexpr (F == Activation::pietras) {
    // 1/(1 + 2^(2x)) = sigmoid(-2 ln2 x)
    return Sigmoid(d, hn::Mul(hn::Set(d, static_cast<float>(-2.0 * std::numbers::ln2)), x));
  } else if constexpr (F == Activation::tanh) {
    return hn::Tanh(d, x);
  } else if constexpr (F == Activation::sigmoid) {
    return Sigmoid(d, x);
  } else if constexpr (F == Activation::relu) {
    return hn::Max(x, hn::Zero(d));
  } else {  // softplus: max(x, 0) + ln(1 + e^-|x|), no overflow
    return hn::Add(hn::Max(x, hn::Zero(d)), hn::Log1p(d, hn::Exp(d, hn::Neg(hn::Abs(x)))));
  }
}

// out[j] = f(sum_i W[j][i] in[i] + b[j]) for one vector of lanes (eq. 5).
template <Activation F, class D>
HWY_INLINE void LayerT(D d, const BatchLayer& l, const float* HWY_RESTRICT in,
                       float* HWY_RESTRICT out) {
  using V = hn::Vec<D>;
  const size_t N = hn::Lanes(d);
  const int n_in = l.n_in;
  int j = 0;
  for (; j + 4 <= l.n_out; j += 4) {
    const float* HWY_RESTRICT w0 = l.w + static_cast<size_t>(j) * n_in;
    const float* HWY_RESTRICT w1 = w0 + n_in;
    const float* HWY_RESTRICT w2 = w1 + n_in;
    const float* HWY_RESTRICT w3 = w2 + n_in;
    V a0 = hn::Set(d, l.b[j]), a1 = hn::Set(d, l.b[j + 1]);
    V a2 = hn::Set(d, l.b[j + 2]), a3 = hn::Set(d, l.b[j + 3]);
    for (int i = 0; i < n_in; ++i) {
      const V x = hn::Load(d, in + i * N);
      a0 = hn::MulAdd(hn::Set(d, w0[i]), x, a0);
      a1 = hn::MulAdd(hn::Set(d, w1[i]), x, a1);
      a2 = hn::MulAdd(hn::Set(d, w2[i]), x, a2);
      a3 = hn::MulAdd(hn::Set(d, w3[i]), x, a3);
    }
    hn::Store(Activate<F>(d, a0), d, out + j * N);
    hn::Store(Activate<F>(d, a1), d, out + (j + 1) * N);
    hn::Store(Activate<F>(d, a2), d, out + (j + 2) * N);
    hn::Store(Activate<F>(d, a3), d, out + (j + 3) * N);
  }
  for (; j < l.n_out; ++j) {
    const float* HWY_RESTRICT w0 = l.w + static_cast<size_t>(j) * n_in;
    V a0 = hn::Set(d, l.b[j]);
    for (int i = 0; i < n_in; ++i) a0 = hn::MulAdd(hn::Set(d, w0[i]), hn::Load(d, in + i * N), a0);
    hn::Store(Activate<F>(d, a0), d, out + j * N);
  }
}

template <class D>
HWY_INLINE void Layer(D d, const BatchLayer& l, const float* HWY_RESTRICT in,
                      float* HWY_RESTRICT out) {
  switch (l.f) {
    case Activation::identity:
      return LayerT<Activation::identity>(d, l, in, out);
    case Activation::satilmis:
      return LayerT<Activation::satilmis>(d, l, in, out);
    case Activation::pietras:
      return LayerT<Activation::pietras>(d, l, in, out);
    case Activation::tanh:
      return LayerT<Activation::tanh>(d, l, in, out);
    case Activation::sigmoid:
      return LayerT<Activation::sigmoid>(d, l, in, out);
    case Activation::relu:
      return LayerT<Activation::relu>(d, l, in, out);
    case Activation::softplus:
      return LayerT<Activation::softplus>(d, l, in, out);
  }
}

// Runs all layers on the vector whose inputs are in a; returns the buffer holding the outputs.
template <class D>
HWY_INLINE const float* RunLayers(D d, const BatchLayer* layers, int n_layers, float* a, float* b) {
  for (int k = 0; k < n_layers; ++k) {
    Layer(d, layers[k], a, b);
    std::swap(a, b);
  }
  return a;
}

void MlpBatchImpl(const BatchLayer* layers, int n_layers, const float* const* inputs,
                  float* const* outputs, size_t n) {
  const hn::ScalableTag<float> d;
  const size_t N = hn::Lanes(d);
  HWY_ALIGN float buf0[detail::kMaxBatchWidth * hn::MaxLanes(d)];
  HWY_ALIGN float buf1[detail::kMaxBatchWidth * hn::MaxLanes(d)];
  const int n_in = layers[0].n_in, n_out = layers[n_layers - 1].n_out;
  for (size_t i = 0; i < n; i += N) {
    const size_t m = std::min(N, n - i);
    if (m == N) {
      for (int k = 0; k < n_in; ++k) hn::Store(hn::LoadU(d, inputs[k] + i), d, buf0 + k * N);
    } else {  // tail: pad with zeros, write back only the real lanes
      for (int k = 0; k < n_in; ++k) {
        for (size_t l = 0; l < N; ++l) buf0[k * N + l] = l < m ? inputs[k][i + l] : 0.0f;
      }
    }
    const float* res = RunLayers(d, layers, n_layers, buf0, buf1);
    for (int c = 0; c < n_out; ++c) {
      if (m == N) {
        hn::StoreU(hn::Load(d, res + c * N), d, outputs[c] + i);
      } else {
        for (size_t l = 0; l < m; ++l) outputs[c][i + l] = res[c * N + l];
      }
    }
  }
}

// A per-direction input of the sky kernel (the chord d is computed once per vector).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V DirectionFeature(D d, const detail::SkyBatchParams& p, detail::DirectionInput k, V x,
                              V y, V z, V chord) {
  using detail::DirectionInput;
  switch (k) {
    case DirectionInput::x:
      return x;
    case DirectionInput::y:
      return y;
    case DirectionInput::z:
      return z;
    case DirectionInput::reference_y:
      return hn::MulAdd(hn::Set(d, p.ry_x), x, hn::Mul(hn::Set(d, p.ry_y), y));
    case DirectionInput::chord:
      return chord;
    case DirectionInput::log_chord:
      return hn::Log(d, hn::Add(chord, hn::Set(d, static_cast<float>(detail::kLogChordOffset))));
    case DirectionInput::aureole:
      return hn::Div(
          hn::Set(d, 1.0f),
          hn::MulAdd(chord, chord, hn::Set(d, static_cast<float>(detail::kAureoleOffset))));
    case DirectionInput::sqrt_z:
      break;
  }
  return hn::Sqrt(hn::Max(z, hn::Zero(d)));
}

// d = |s - v| = 2 sin(gamma/2).
template <class D, class V = hn::Vec<D>>
HWY_INLINE V Chord(D /*d*/, V x, V y, V z, V sx, V sy, V sz) {
  const V dx = hn::Sub(x, sx), dy = hn::Sub(y, sy), dz = hn::Sub(z, sz);
  return hn::Sqrt(hn::MulAdd(dx, dx, hn::MulAdd(dy, dy, hn::Mul(dz, dz))));
}

// Radiance of one channel from the last layer's output o, 0 below the horizon.
template <class D, class M, class V = hn::Vec<D>>
HWY_INLINE V SkyOutput(D d, const detail::SkyBatchParams& p, M above, V o) {
  using detail::SkyBatchOutput;
  V L;
  switch (p.output) {
    case SkyBatchOutput::squared:
      L = hn::Mul(o, o);
      break;
    case SkyBatchOutput::power4: {
      const V o2 = hn::Mul(o, o);
      L = hn::Mul(o2, o2);
      break;
    }
    case SkyBatchOutput::power8: {
      const V o2 = hn::Mul(o, o);
      const V o4 = hn::Mul(o2, o2);
      L = hn::Mul(o4, o4);
      break;
    }
    case SkyBatchOutput::inverse_ls: {  // scale 0.5 (1/y - 1), y clamped away from 0
      const V inv = hn::Div(hn::Set(d, 1.0f), hn::Max(o, hn::Set(d, 1e-30f)));
      L = hn::Mul(hn::Set(d, 0.5f * p.scale), hn::Sub(inv, hn::Set(d, 1.0f)));
      break;
    }
    case SkyBatchOutput::exp:
    default:
      L = hn::Mul(hn::Set(d, p.scale), hn::Exp(d, o));
      break;
  }
  return hn::IfThenElseZero(above, hn::Min(L, hn::Set(d, p.max_value)));
}

// Calls block(x, y, z, out) for every block of kVectors * N directions (out[c] points to kVectors
// * N floats of channel c); the tail is padded with the zenith direction and copied back.
template <int kVectors, class D, class Block>
HWY_INLINE void ForEachBlock(D d, const float* HWY_RESTRICT px, const float* HWY_RESTRICT py,
                             const float* HWY_RESTRICT pz, float* const outs[3], size_t n,
                             const Block& block) {
  const size_t N = hn::Lanes(d), B = kVectors * N;
  size_t i = 0;
  for (; i + B <= n; i += B) {
    float* o[3] = {outs[0] + i, outs[1] + i, outs[2] + i};
    block(px + i, py + i, pz + i, o);
  }
  if (i == n) return;
  HWY_ALIGN float tx[kVectors * hn::MaxLanes(d)], ty[kVectors * hn::MaxLanes(d)];
  HWY_ALIGN float tz[kVectors * hn::MaxLanes(d)], t0[kVectors * hn::MaxLanes(d)];
  HWY_ALIGN float t1[kVectors * hn::MaxLanes(d)], t2[kVectors * hn::MaxLanes(d)];
  for (size_t l = 0; l < B; ++l) {
    const bool real = i + l < n;
    tx[l] = real ? px[i + l] : 0.0f;
    ty[l] = real ? py[i + l] : 0.0f;
    tz[l] = real ? pz[i + l] : 1.0f;
  }
  float* o[3] = {t0, t1, t2};
  block(tx, ty, tz, o);
  for (size_t l = 0; i + l < n; ++l) {
    outs[0][i + l] = t0[l];
    outs[1][i + l] = t1[l];
    outs[2][i + l] = t2[l];
  }
}

// Any layout: per vector, the direction inputs go to the scratch buffer and RunLayers does the
// rest.
void SkyGeneric(const detail::SkyBatchParams& p, const float* px, const float* py, const float* pz,
                float* const outs[3], size_t n) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const size_t N = hn::Lanes(d);
  HWY_ALIGN float buf0[detail::kMaxBatchWidth * hn::MaxLanes(d)];
  HWY_ALIGN float buf1[detail::kMaxBatchWidth * hn::MaxLanes(d)];
  const V sx = hn::Set(d, p.sx), sy = hn::Set(d, p.sy), sz = hn::Set(d, p.sz);
  ForEachBlock<1>(
      d, px, py, pz, outs, n,
      [&](const float* bx, const float* by, const float* bz, float* const o[3]) {
        const V x = hn::LoadU(d, bx), y = hn::LoadU(d, by), z = hn::LoadU(d, bz);
        const auto above = hn::Ge(z, hn::Zero(d));
        if (hn::AllFalse(d, above)) {  // the whole vector is below the horizon: the sky is 0 there
          for (int c = 0; c < 3; ++c) hn::StoreU(hn::Zero(d), d, o[c]);
          return;
        }
        const V chord = Chord(d, x, y, z, sx, sy, sz);
        for (int k = 0; k < p.n_inputs; ++k) {
          hn::Store(DirectionFeature(d, p, p.inputs[k], x, y, z, chord), d, buf0 + k * N);
        }
        const float* res = RunLayers(d, p.layers, p.n_layers, buf0, buf1);
        for (int c = 0; c < 3; ++c) {
          hn::StoreU(SkyOutput(d, p, above, hn::Load(d, res + c * N)), d, o[c]);
        }
      });
}

#if !HWY_HAVE_SCALABLE
// One hidden layer of H satilmis neurons, NI direction inputs, 3 identity outputs (the paper's
// network after SkyNetworkBatch's folds), fully unrolled: each hidden activation goes straight
// into the three output accumulators (nothing stored), and two vectors share every weight
// broadcast.
template <int NI, int H>
void SkyOneHidden(const detail::SkyBatchParams& p, const float* px, const float* py,
                  const float* pz, float* const outs[3], size_t n) {
  const hn::ScalableTag<float> d;
  using V = hn::Vec<decltype(d)>;
  const size_t N = hn::Lanes(d);
  const V sx = hn::Set(d, p.sx), sy = hn::Set(d, p.sy), sz = hn::Set(d, p.sz);
  const float* HWY_RESTRICT W1 = p.layers[0].w;
  const float* HWY_RESTRICT b1 = p.layers[0].b;
  const float* HWY_RESTRICT W2 = p.layers[1].w;
  const float* HWY_RESTRICT b2 = p.layers[1].b;
  ForEachBlock<2>(d, px, py, pz, outs, n,
                  [&](const float* bx, const float* by, const float* bz, float* const o[3]) {
                    const V za = hn::LoadU(d, bz), zb = hn::LoadU(d, bz + N);
                    const auto above_a = hn::Ge(za, hn::Zero(d)), above_b = hn::Ge(zb, hn::Zero(d));
                    if (hn::AllFalse(d, hn::Or(above_a, above_b))) {
                      for (int c = 0; c < 3; ++c) {
                        hn::StoreU(hn::Zero(d), d, o[c]);
                        hn::StoreU(hn::Zero(d), d, o[c] + N);
                      }
                      return;
                    }
                    const V xa = hn::LoadU(d, bx), xb = hn::LoadU(d, bx + N);
                    const V ya = hn::LoadU(d, by), yb = hn::LoadU(d, by + N);
                    const V ca = Chord(d, xa, ya, za, sx, sy, sz);
                    const V cb = Chord(d, xb, yb, zb, sx, sy, sz);
                    V ia[NI], ib[NI];
                    for (int k = 0; k < NI; ++k) {
                      ia[k] = DirectionFeature(d, p, p.inputs[k], xa, ya, za, ca);
                      ib[k] = DirectionFeature(d, p, p.inputs[k], xb, yb, zb, cb);
                    }
                    V oa0 = hn::Set(d, b2[0]), oa1 = hn::Set(d, b2[1]), oa2 = hn::Set(d, b2[2]);
                    V ob0 = oa0, ob1 = oa1, ob2 = oa2;
#pragma GCC unroll 64
                    for (int j = 0; j < H; ++j) {
                      V aa = hn::Set(d, b1[j]);
                      V ab = aa;
#pragma GCC unroll 16
                      for (int i = 0; i < NI; ++i) {
                        const V w = hn::Set(d, W1[j * NI + i]);
                        aa = hn::MulAdd(w, ia[i], aa);
                        ab = hn::MulAdd(w, ib[i], ab);
                      }
                      const V ha = Satilmis(d, aa), hb = Satilmis(d, ab);
                      const V w0 = hn::Set(d, W2[j]), w1 = hn::Set(d, W2[H + j]),
                              w2 = hn::Set(d, W2[2 * H + j]);
                      oa0 = hn::MulAdd(w0, ha, oa0);
                      ob0 = hn::MulAdd(w0, hb, ob0);
                      oa1 = hn::MulAdd(w1, ha, oa1);
                      ob1 = hn::MulAdd(w1, hb, ob1);
                      oa2 = hn::MulAdd(w2, ha, oa2);
                      ob2 = hn::MulAdd(w2, hb, ob2);
                    }
                    hn::StoreU(SkyOutput(d, p, above_a, oa0), d, o[0]);
                    hn::StoreU(SkyOutput(d, p, above_b, ob0), d, o[0] + N);
                    hn::StoreU(SkyOutput(d, p, above_a, oa1), d, o[1]);
                    hn::StoreU(SkyOutput(d, p, above_b, ob1), d, o[1] + N);
                    hn::StoreU(SkyOutput(d, p, above_a, oa2), d, o[2]);
                    hn::StoreU(SkyOutput(d, p, above_b, ob2), d, o[2] + N);
                  });
}

using SkyKernelFn = void (*)(const detail::SkyBatchParams&, const float*, const float*,
                             const float*, float* const[3], size_t);

template <int NI>
SkyKernelFn OneHiddenForWidth(int H) {
  switch (H) {
    case 4:
      return &SkyOneHidden<NI, 4>;
    case 8:
      return &SkyOneHidden<NI, 8>;
    case 12:
      return &SkyOneHidden<NI, 12>;
    case 16:
      return &SkyOneHidden<NI, 16>;
    case 24:
      return &SkyOneHidden<NI, 24>;
    case 32:
      return &SkyOneHidden<NI, 32>;
    case 48:
      return &SkyOneHidden<NI, 48>;
    default:
      return nullptr;
  }
}

// The unrolled kernel for this layout, or nullptr.
SkyKernelFn OneHiddenKernel(const detail::SkyBatchParams& p) {
  if (p.n_layers != 2 || p.layers[0].f != Activation::satilmis ||
      p.layers[1].f != Activation::identity || p.layers[1].n_out != 3 ||
      p.layers[0].n_in != p.n_inputs) {
    return nullptr;
  }
  switch (p.n_inputs) {
    case 3:
      return OneHiddenForWidth<3>(p.layers[0].n_out);
    case 4:
      return OneHiddenForWidth<4>(p.layers[0].n_out);
    case 5:
      return OneHiddenForWidth<5>(p.layers[0].n_out);
    default:
      return nullptr;
  }
}
#endif  // !HWY_HAVE_SCALABLE

void SkyBatchImpl(const detail::SkyBatchParams& p, const float* px, const float* py,
                  const float* pz, float* r, float* g, float* b, size_t n) {
  float* const outs[3] = {r, g, b};
#if !HWY_HAVE_SCALABLE
  if (const SkyKernelFn f = p.allow_unrolled ? OneHiddenKernel(p) : nullptr) {
    return f(p, px, py, pz, outs, n);
  }
#endif
  SkyGeneric(p, px, py, pz, outs, n);
}

}  // namespace HWY_NAMESPACE
}  // namespace skylight::nn
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace skylight::nn {

HWY_EXPORT(MlpBatchImpl);
HWY_EXPORT(SkyBatchImpl);

namespace detail {

void mlp_batch(const BatchLayer* layers, int n_layers, const float* const* inputs,
               float* const* outputs, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(MlpBatchImpl)(layers, n_layers, inputs, outputs, n);
}

void sky_batch(const SkyBatchParams& p, const float* x, const float* y, const float* z, float* r,
               float* g, float* b, std::size_t n) {
  HWY_DYNAMIC_DISPATCH(SkyBatchImpl)(p, x, y, z, r, g, b, n);
}

}  // namespace detail
}  // namespace skylight::nn
#endif  // HWY_ONCE
