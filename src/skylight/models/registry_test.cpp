#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "skylight/core/error.h"
#include "skylight/models/sky_model.h"
#include "support/scratch_dir.h"

namespace skylight {
namespace {

TEST(Registry, UnknownModelAndBadParameters) {
  SkyParameters p;
  EXPECT_THROW(make_sky_model("nope", p), InvalidArgument);
  p.sun.zenith = std::nan("");
  EXPECT_THROW(make_sky_model("preetham", p), InvalidArgument);
  SkyParameters q;
  EXPECT_THROW(make_sky_model("perez", q), InvalidArgument) << "perez needs coefficients";
  q.values.set("perez", std::vector<double>{-1, -0.32, 10, -3, 0.45});
  EXPECT_THROW(make_sky_model("perez", q), InvalidArgument) << "perez needs a zenith luminance";
  q.values.set("zenith-luminance", 100.0);
  EXPECT_NO_THROW(make_sky_model("perez", q));
  q.values.set("perez", std::vector<double>{-2, 0.5, 0, 0, 0});  // F(0) = 1 - 2 e^0.5 < 0
  EXPECT_THROW(make_sky_model("perez", q), InvalidArgument);
  for (const auto& info : model_registry()) {
    EXPECT_FALSE(info.parameters.empty()) << info.name;
    for (const auto& par : info.parameters)
      EXPECT_LE(par.min, par.max) << info.name << " " << par.name;
  }
}

TEST(Registry, EveryParameterHasAUsableSpec) {
  for (const auto& info : model_registry()) {
    for (const auto& p : all_parameters(info)) {
      EXPECT_FALSE(p.description.empty()) << info.name << " " << p.name;
      EXPECT_EQ(p.name.find_first_of(" _="), std::string::npos) << p.name;
      // A typed default lies in the range.
      if (const auto* v = std::get_if<ParameterValue>(&p.default_value)) {
        EXPECT_NO_THROW(p.check(*v)) << info.name << " " << p.name;
      }
    }
    // The defaults (and the example values for required parameters) build the model.
    SkyParameters sp;
    sp.values = info.example;
    EXPECT_NO_THROW(info.make(sp)) << info.name;
  }
}

// A report policy's source is a registered model the report can draw at the same axis value, and
// its axis range lies within the axis parameter's range.
TEST(Registry, ReportSourcesAreComparableModels) {
  for (const auto& info : model_registry()) {
    SCOPED_TRACE(info.name);
    const ReportPolicy& r = info.report;
    if (r.axis_range) {
      const ParameterSpec* p = info.find_parameter(r.axis);
      ASSERT_NE(p, nullptr);
      EXPECT_LE(p->min, (*r.axis_range)[0]);
      EXPECT_LT((*r.axis_range)[0], (*r.axis_range)[1]);
      EXPECT_LE((*r.axis_range)[1], p->max);
    }
    if (!r.truncation.empty()) {
      EXPECT_FALSE(r.source.empty()) << "a truncation is measured against a source";
      const ParameterSpec* t = info.find_parameter(r.truncation);
      ASSERT_NE(t, nullptr);
      EXPECT_EQ(t->kind, ParameterKind::integer);
      EXPECT_LE(t->min, r.truncation_range[0]);
      EXPECT_LE(r.truncation_range[0], r.truncation_range[1]);
      EXPECT_LE(r.truncation_range[1], t->max);
    }
    if (r.source.empty()) continue;
    const ModelInfo* source = find_model(r.source);
    ASSERT_NE(source, nullptr);
    EXPECT_NE(source->name, info.name);
    EXPECT_FALSE(source->report.title.empty());
    EXPECT_EQ(source->report.axis, r.axis);
  }
}

TEST(Registry, ModelsReportWhatTheyReadAsParameterValues) {
  for (const auto& info : model_registry()) {
    SkyParameters sp;
    sp.values = info.example;
    const auto m = info.make(sp);
    const ParameterValues read = m->parameter_values();
    for (const auto& [name, value] : read.all()) {
      const auto it =
          std::find_if(info.parameters.begin(), info.parameters.end(),
                       [&name = name](const ParameterSpec& s) { return s.name == name; });
      ASSERT_NE(it, info.parameters.end()) << info.name << " reports '" << name << "'";
      EXPECT_NO_THROW(it->check(value)) << info.name << " " << name;
    }
    // Feeding them back builds the same sky.
    SkyParameters again;
    again.values = read;
    const auto m2 = info.make(again);
    const Vec3 v = direction_from_angles(1.0, 2.0);
    EXPECT_EQ(m2->tristimulus(v).Y, m->tristimulus(v).Y) << info.name;
  }
}

// Every model at the edges of its domain: each numeric parameter at its min, max and default, the
// sun at the zenith, the horizon and below it; the scalar and the batch paths over directions
// that include the horizon, the nadir and the sun. Nothing non-finite, no negative luminance
// (except from the models that declare their output unclamped: `sh`).
// The sweep of part `part` of `parts` of the parameter variants (each variant of a costly model is
// a table of its own: the parts keep each test under a minute).
void sweep_edges(const std::string& model, int part = 0, int parts = 1);
class EdgeSweeps : public ::testing::TestWithParam<std::string> {};
TEST_P(EdgeSweeps, GiveFiniteNonNegativeOutput) {
  sweep_edges(GetParam());
}
// The same for the models whose set-up is costly (ModelInfo::costly_setup), a suite of their own,
// in kCostlySweepParts parts each.
constexpr int kCostlySweepParts = 3;
class CostlyEdgeSweeps : public ::testing::TestWithParam<std::pair<std::string, int>> {};
TEST_P(CostlyEdgeSweeps, GiveFiniteNonNegativeOutput) {
  sweep_edges(GetParam().first, GetParam().second, kCostlySweepParts);
}

void sweep_edges(const std::string& model, int part, int parts) {
  std::vector<Vec3> dirs;
  for (int it = 0; it <= 18; ++it)
    for (int ip = 0; ip < 8; ++ip)
      dirs.push_back(direction_from_angles(it * 10.0 * kDegree, ip * 45.0 * kDegree));
  for (double z : {89.99, 90.0, 90.01}) dirs.push_back(direction_from_angles(z * kDegree, kPi));
  std::size_t models_built = 0, evaluations = 0;
  {
    const ModelInfo& info = *find_model(model);
    // The example, with the values the sweeps hold (ModelInfo::sweep).
    ParameterValues base = info.example;
    for (const auto& [name, value] : info.sweep.all()) base.set(name, value);
    std::vector<ParameterValues> variants{base};
    for (const auto& spec : info.parameters) {
      if (spec.kind != ParameterKind::number && spec.kind != ParameterKind::integer) continue;
      if (info.sweep.has(spec.name)) continue;
      for (double v : {spec.min, spec.max}) {
        ParameterValues p = base;
        p.set(spec.name, v);
        variants.push_back(p);
      }
    }
    for (std::size_t k = 0; k < variants.size(); ++k) {
      if (static_cast<int>(k % static_cast<std::size_t>(parts)) != part) continue;
      const ParameterValues& values = variants[k];
      for (double sun_zenith_deg : {0.0, 45.0, 89.9, 90.0, 90.1, 120.0}) {
        SkyParameters sp;
        sp.sun = {sun_zenith_deg * kDegree, kPi};
        sp.values = values;
        std::unique_ptr<SkyModel> m;
        try {
          m = info.make(sp);
        } catch (const InvalidArgument&) {
          continue;  // refused with a message: allowed (e.g. a top radius below the ground)
        }
        ++models_built;
        // An observer above the ground sees below its local horizontal (the sun too).
        const bool above_ground = values.number("observer-altitude").value_or(0.0) > 0.0;
        std::vector<Vec3> all = dirs;
        all.push_back(sp.sun.direction());
        std::vector<float> x, y, z;
        for (const Vec3& d : all) {
          x.push_back(static_cast<float>(d.x));
          y.push_back(static_cast<float>(d.y));
          z.push_back(static_cast<float>(d.z));
        }
        std::vector<float> X(all.size()), Y(all.size()), Z(all.size());
        m->tristimulus_batch({x, y, z}, {X, Y, Z});
        for (std::size_t i = 0; i < all.size(); ++i) {
          const Xyz c = m->tristimulus(all[i]);
          const Xyz s = m->sun_tristimulus(all[i]);
          ++evaluations;
          const bool ok = std::isfinite(c.X) && std::isfinite(c.Y) && std::isfinite(c.Z) &&
                          (c.Y >= 0.0 || info.unclamped) && std::isfinite(s.Y) && s.Y >= 0.0 &&
                          std::isfinite(X[i]) && std::isfinite(Y[i]) && std::isfinite(Z[i]) &&
                          (Y[i] >= 0.0f || info.unclamped) &&
                          (all[i].z >= 0.0 || s.Y == 0.0 || above_ground);
          ASSERT_TRUE(ok) << info.name << " sun zenith " << sun_zenith_deg << " view " << all[i].x
                          << "," << all[i].y << "," << all[i].z << ": Y " << c.Y << " batch "
                          << Y[i] << " sun " << s.Y;
        }
      }
    }
  }
  std::printf("edge sweeps: %zu models, %zu directions each way\n", models_built, evaluations);
}

std::vector<std::string> model_names(bool costly) {
  std::vector<std::string> names;
  for (const auto& info : model_registry())
    if (info.costly_setup == costly) names.push_back(info.name);
  return names;
}
INSTANTIATE_TEST_SUITE_P(Registry, EdgeSweeps, ::testing::ValuesIn(model_names(false)),
                         [](const auto& param) { return param.param; });
std::vector<std::pair<std::string, int>> costly_sweep_parts() {
  std::vector<std::pair<std::string, int>> out;
  for (const std::string& name : model_names(true))
    for (int part = 0; part < kCostlySweepParts; ++part) out.emplace_back(name, part);
  return out;
}
INSTANTIATE_TEST_SUITE_P(Registry, CostlyEdgeSweeps, ::testing::ValuesIn(costly_sweep_parts()),
                         [](const auto& param) {
                           return param.param.first + "_part" + std::to_string(param.param.second);
                         });

// Exactly one model is the report's physical atmosphere (its colour and twilight reference).
TEST(Registry, OneModelIsThePhysicalReference) {
  int n = 0;
  for (const auto& info : model_registry())
    if (info.report.physical_reference) {
      ++n;
      EXPECT_FALSE(info.report.title.empty()) << info.name;
    }
  EXPECT_EQ(n, 1);
}

// README.md's --model row names every model of the registry, and nothing else.
TEST(Registry, ReadmeModelFlagListsEveryModel) {
  const std::string readme = testing_support::source_file("README.md");
  const std::size_t at = readme.find("| `--model NAME` |");
  ASSERT_NE(at, std::string::npos) << "README.md: no --model NAME row";
  const std::string row = readme.substr(at, readme.find('\n', at) - at);
  std::size_t named = 0;
  for (std::size_t p = row.find('`'); p != std::string::npos; p = row.find('`', p + 1)) {
    const std::size_t end = row.find('`', p + 1);
    ASSERT_NE(end, std::string::npos) << row;
    const std::string word = row.substr(p + 1, end - p - 1);
    if (find_model(word)) ++named;
    p = end;
  }
  for (const auto& info : model_registry())
    EXPECT_NE(row.find("`" + info.name + "`"), std::string::npos) << info.name << ": " << row;
  EXPECT_EQ(named, model_registry().size()) << row;
}

// docs/MODELS.md shows each model's parameter table as generated from the schema; a change of
// either without the other fails here (regenerate with `skylight models --markdown`).
TEST(Registry, DocsParameterTablesMatchTheSchema) {
  const std::string doc = testing_support::source_file("docs/MODELS.md");
  ASSERT_FALSE(doc.empty()) << "docs/MODELS.md not found";
  for (const auto& info : model_registry()) {
    const std::string block = parameter_docs_block(info);
    EXPECT_NE(doc.find(block), std::string::npos)
        << "docs/MODELS.md lacks this table of '" << info.name << "':\n"
        << block;
  }
}

}  // namespace
}  // namespace skylight
