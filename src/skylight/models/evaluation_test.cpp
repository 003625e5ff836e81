// The batch entry points of models/evaluation.h against the model's own paths: evaluate_rows and
// evaluate_soa are the SIMD batch (tristimulus_batch) on the same float directions, bit for bit,
// and evaluate() per direction when exact; bad directions and overflow are named errors.
#include "skylight/models/evaluation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/core/parallel.h"

namespace skylight {
namespace {

std::unique_ptr<SkyModel> preetham() {
  SkyParameters p;
  p.sun = {.zenith = deg_to_rad(40.0), .azimuth = deg_to_rad(150.0)};
  p.values.set("turbidity", 3.0);
  return make_sky_model("preetham", p);
}

// n random unit directions (both hemispheres) as float64 rows, unit in float64 arithmetic.
std::vector<double> rows_of(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::vector<double> rows;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 v = normalize(Vec3{g(rng), g(rng), g(rng)});
    rows.insert(rows.end(), {v.x, v.y, v.z});
  }
  return rows;
}

EvaluationOptions xyz() {
  EvaluationOptions o;
  o.quantity = Quantity::xyz;
  return o;
}

// More directions than a parallel_for chunk holds, and not a multiple of any vector width.
constexpr std::size_t kDirections = 3 * kBatchChunk * 16 + 37;

TEST(Evaluation, RowsAndSoaAreTheBatchPathBitForBit) {
  const auto m = preetham();
  const std::vector<double> rows = rows_of(kDirections, 1);
  const std::size_t n = kDirections;
  std::vector<float> x(n), y(n), z(n), X(n), Y(n), Z(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = static_cast<float>(rows[3 * i]);
    y[i] = static_cast<float>(rows[3 * i + 1]);
    z[i] = static_cast<float>(rows[3 * i + 2]);
  }
  m->tristimulus_batch({x, y, z}, {X, Y, Z});
  for (const int threads : {1, 2}) {
    const ScopedThreadCount count(threads);
    std::vector<double> out(3 * n), lum(n);
    evaluate_rows(*m, rows, xyz(), out);
    EvaluationOptions l;
    l.quantity = Quantity::luminance;
    evaluate_rows(*m, rows, l, lum);
    std::vector<float> sX(n), sY(n), sZ(n);
    evaluate_soa(*m, {x, y, z}, {sX, sY, sZ});
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(out[3 * i], X[i]) << i;
      ASSERT_EQ(out[3 * i + 1], Y[i]) << i;
      ASSERT_EQ(out[3 * i + 2], Z[i]) << i;
      ASSERT_EQ(lum[i], Y[i]) << i;
      ASSERT_EQ(sX[i], X[i]) << i;
      ASSERT_EQ(sY[i], Y[i]) << i;
      ASSERT_EQ(sZ[i], Z[i]) << i;
    }
  }
}

TEST(Evaluation, ExactRowsAndAnglesAreEvaluatePerDirection) {
  const auto m = preetham();
  const std::vector<double> rows = rows_of(500, 2);
  std::vector<double> zen, azi;
  for (std::size_t i = 0; i < 500; ++i) {
    const Vec3 v{rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]};
    zen.push_back(rad_to_deg(std::acos(std::clamp(v.z, -1.0, 1.0))));
    azi.push_back(rad_to_deg(std::atan2(v.x, v.y)));
  }
  for (const Quantity q : {Quantity::rgb, Quantity::xyz, Quantity::luminance}) {
    EvaluationOptions o;
    o.quantity = q;
    const std::size_t cols = quantity_columns(o).size();
    std::vector<double> out(500 * cols), by_angle(500 * cols);
    evaluate_rows(*m, rows, o, out, /*exact=*/true);
    evaluate_angles(*m, zen, azi, o, by_angle, /*exact=*/true);
    for (std::size_t i = 0; i < 500; ++i) {
      const Vec3 v{rows[3 * i], rows[3 * i + 1], rows[3 * i + 2]};
      const std::vector<double> want = evaluate(*m, (1.0 / std::sqrt(dot(v, v))) * v, o);
      const std::vector<double> want_angle = evaluate(
          *m, direction_from_angles(deg_to_rad(zen[i]), wrap_azimuth(deg_to_rad(azi[i]))), o);
      for (std::size_t c = 0; c < cols; ++c) {
        ASSERT_EQ(out[i * cols + c], want[c]) << i;
        ASSERT_EQ(by_angle[i * cols + c], want_angle[c]) << i;
      }
    }
  }
}

TEST(Evaluation, NonUnitRowsAreNormalised) {
  const auto m = preetham();
  std::vector<double> rows = rows_of(100, 3), scaled = rows;
  for (std::size_t i = 0; i < scaled.size(); ++i) scaled[i] *= 1.0 + static_cast<double>(i / 3 % 7);
  std::vector<double> a(300), b(300);
  evaluate_rows(*m, rows, xyz(), a);
  evaluate_rows(*m, scaled, xyz(), b);
  // The scaled rows are divided by their length in double, then rounded to float: the float
  // directions equal the unit ones' to within one rounding, and the batch path's sensitivity to a
  // one-ulp direction change is far below its own tolerance.
  constexpr double kOneUlpDirection = 1e-5;
  for (std::size_t i = 0; i < 300; ++i)
    EXPECT_NEAR(a[i], b[i], kOneUlpDirection * std::max(1.0, std::abs(a[i]))) << i;
}

TEST(Evaluation, BadInputIsANamedError) {
  const auto m = preetham();
  std::vector<double> rows = rows_of(kDirections, 4);
  std::vector<double> out(3 * kDirections);
  const std::size_t bad = 2 * kBatchChunk + 5;
  rows[3 * bad] = std::numeric_limits<double>::quiet_NaN();
  try {
    evaluate_rows(*m, rows, xyz(), out);
    FAIL() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("direction " + std::to_string(bad) + " ="),
              std::string::npos)
        << e.what();
  }
  rows[3 * bad] = rows[3 * bad + 1] = rows[3 * bad + 2] = 0.0;
  EXPECT_THROW(evaluate_rows(*m, rows, xyz(), out, /*exact=*/true), InvalidArgument);
  EXPECT_THROW(evaluate_rows(*m, std::span<const double>(rows).first(4), xyz(), out),
               InvalidArgument);
  std::vector<double> small(5);
  EXPECT_THROW(evaluate_rows(*m, rows, xyz(), small), InvalidArgument);

  std::vector<float> x(10, 0.0f), y(10, 0.0f), z(10, 1.0f), X(10), Y(10), Z(10);
  z[7] = 1.01f;
  try {
    evaluate_soa(*m, {x, y, z}, {X, Y, Z});
    FAIL() << "no error";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("direction 7 ="), std::string::npos) << e.what();
  }
  std::vector<float> short_out(9);
  EXPECT_THROW(evaluate_soa(*m, {x, y, z}, {short_out, Y, Z}), InvalidArgument);
  const std::vector<double> zen{10.0, 190.0}, azi{0.0, 0.0};
  std::vector<double> two(6);
  EXPECT_THROW(evaluate_angles(*m, zen, azi, xyz(), two), InvalidArgument);
}

}  // namespace
}  // namespace skylight
