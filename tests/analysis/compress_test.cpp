// Wavelet compression (core/analysis/compress.h, docs/compression.md) on hierarchies with real detail
// (tests/compress_fixture.h: a bundled shape refined J times, bent by smooth waves of three
// lengths and roughened by a little Gaussian noise, then analysed). Checks the error measures
// against their definition, the ranking against keep_largest and an independent recomputation
// of |w| 2^(-j dim / 2), the three modes, regions and the session's gains.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <set>

#include <gtest/gtest.h>

#include "core/base/bounds.h"
#include "core/analysis/compress.h"
#include "core/base/errors.h"
#include "core/analysis/experiments.h"
#include "core/edit/session.h"
#include "core/io/lattice/shape_io.h"
#include "tests/compress_fixture.h"

using namespace sublift;

namespace {

const std::string kAssets = SUBLIFT_ASSETS_DIR;

Hierarchy detailed(const std::string& asset, Scheme scheme, int levels) {
  return sublift::testing::detailed_hierarchy(kAssets + "/" + asset, scheme, levels);
}

struct Case {
  const char* name;
  const char* asset;
  Scheme scheme;
  int levels;
};

// Every scheme on a surface, and a lattice; about 5-6 k finest vertices each.
const Case kCases[] = {
    {"linear_torus", "torus_quad.obj", Scheme::Linear, 3},
    {"cubic_torus", "torus_quad.obj", Scheme::Cubic, 3},
    {"sqrt2_torus", "torus_quad.obj", Scheme::Sqrt2, 6},
    {"cubic_lattice", "hex_block_4.lattice", Scheme::Cubic, 2},
};

// |p - q| over finest vertices: the definition of the errors, written out again.
void reference_errors(const std::vector<double>& a, const std::vector<double>& ref, double& rms, double& max) {
  const double d = bbox_diagonal(ref);
  double s = 0;
  max = 0;
  for (std::size_t i = 0; i < a.size(); i += 3) {
    const double e = std::hypot(a[i] - ref[i], a[i + 1] - ref[i + 1], a[i + 2] - ref[i + 2]);
    s += e * e;
    max = std::max(max, e);
  }
  rms = std::sqrt(s / double(a.size() / 3)) / d;
  max /= d;
}

// Level of the wavelet on fine vertex v.
int level_of(const Hierarchy& h, std::uint32_t v) {
  int j = 0;
  while (v >= h.num_vertices(j + 1)) ++j;
  return j;
}

// The wavelets a compression zeroed that were not zero before.
std::set<std::uint32_t> zeroed(const Hierarchy& h, const std::vector<double>& c) {
  std::set<std::uint32_t> out;
  for (std::uint32_t v = h.num_vertices(0); v < h.num_vertices(h.finest_level()); ++v) {
    const double* a = &h.coeffs[3 * std::size_t(v)];
    const double* b = &c[3 * std::size_t(v)];
    if ((a[0] != 0 || a[1] != 0 || a[2] != 0) && b[0] == 0 && b[1] == 0 && b[2] == 0) out.insert(v);
  }
  return out;
}

}  // namespace

TEST(Compress, L2ErrorNonIncreasingAlongFractionsAndZeroAtOne) {
  for (const Case& k : kCases) {
    SCOPED_TRACE(k.name);
    const Hierarchy h = detailed(k.asset, k.scheme, k.levels);
    const Compressor c(h);
    const std::vector<double> full = synthesize(h, h.finest_level());
    EXPECT_EQ(c.total(), h.num_vertices(h.finest_level()) - h.num_vertices(0));
    EXPECT_EQ(c.candidates(), c.total());
    double previous = HUGE_VAL;
    for (const double f : {0.0, 0.01, 0.05, 0.2, 0.5, 1.0}) {
      const Compression r = c.evaluate(c.count_for_fraction(f));
      EXPECT_EQ(r.kept, static_cast<std::size_t>(std::llround(f * double(c.total()))));
      double rms = 0, max = 0;
      reference_errors(r.finest, full, rms, max);
      EXPECT_NEAR(r.l2_error, rms, 1e-12 * (1 + rms)) << f;
      EXPECT_NEAR(r.linf_error, max, 1e-12 * (1 + max)) << f;
      EXPECT_LE(r.l2_error, previous) << "fraction " << f;
      EXPECT_LE(r.l2_error, r.linf_error);
      previous = r.l2_error;
    }
    const Compression all = c.evaluate(c.candidates());
    EXPECT_EQ(all.l2_error, 0.0);
    EXPECT_EQ(all.linf_error, 0.0);
    EXPECT_EQ(all.finest, full);  // bit for bit: the same synthesis
    EXPECT_GT(c.evaluate(0).l2_error, 1e-3) << "the fixture has no real detail";
  }
}

TEST(Compress, KeepSelectsWhatKeepLargestSelectsAndIsProgressive) {
  for (const Case& k : kCases) {
    SCOPED_TRACE(k.name);
    const Hierarchy h = detailed(k.asset, k.scheme, k.levels);
    const Compressor c(h);
    std::set<std::uint32_t> before = zeroed(h, c.coefficients(0));
    for (const double f : {0.01, 0.05, 0.2, 0.5}) {
      Hierarchy copy = h;
      const std::size_t kept = keep_largest(copy, f);
      const std::vector<double> mine = c.coefficients(c.count_for_fraction(f));
      EXPECT_EQ(c.count_for_fraction(f), kept);
      EXPECT_EQ(std::memcmp(mine.data(), copy.coeffs.data(), mine.size() * sizeof(double)), 0) << f;
      // Keeping more keeps a superset: what is zeroed now was zeroed at every smaller fraction.
      const std::set<std::uint32_t> now = zeroed(h, mine);
      EXPECT_TRUE(std::includes(before.begin(), before.end(), now.begin(), now.end())) << f;
      EXPECT_LT(now.size(), before.size());
      before = now;
    }
    // The magnitudes are non-increasing along the ranking.
    EXPECT_TRUE(std::is_sorted(c.magnitudes().rbegin(), c.magnitudes().rend()));
  }
}

// rank_wavelets is the one ranking: keep_ranked on it is keep_largest, bit for bit, and the
// Compressor's order and magnitudes are its entries (raw: no norm factor); the loop scheme
// carries exact norms.
TEST(Compress, RankWaveletsIsKeepLargestsAndTheCompressorsRanking) {
  std::vector<Case> cases(std::begin(kCases), std::end(kCases));
  cases.push_back({"loop_octahedron", "octahedron.obj", Scheme::Loop, 4});
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    const Hierarchy h = detailed(k.asset, k.scheme, k.levels);
    const std::vector<RankedWavelet> ranking = rank_wavelets(h, wavelet_l2_norms(h));
    ASSERT_EQ(ranking.size(), std::size_t(h.num_vertices(h.finest_level()) - h.num_vertices(0)));
    for (const double f : {0.0, 0.01, 0.2, 0.5, 1.0}) {
      Hierarchy a = h, b = h;
      EXPECT_EQ(keep_ranked(a, ranking, f), keep_largest(b, f)) << f;
      EXPECT_EQ(std::memcmp(a.coeffs.data(), b.coeffs.data(), a.coeffs.size() * sizeof(double)), 0) << f;
    }
    for (const bool normalise : {true, false}) {
      CompressOptions o;
      o.normalise = normalise;
      const Compressor c(h, o);
      const std::vector<RankedWavelet> r = rank_wavelets(h, normalise ? wavelet_l2_norms(h) : std::vector<double>{});
      ASSERT_EQ(c.candidates(), r.size());
      for (std::size_t i = 0; i < r.size(); ++i) {
        ASSERT_EQ(c.order()[i], r[i].index) << i;
        ASSERT_EQ(c.magnitudes()[i], r[i].magnitude) << i;
      }
    }
    Hierarchy a = h;
    EXPECT_THROW(keep_ranked(a, ranking, 1.5), Error);
    EXPECT_THROW(rank_wavelets(h, std::vector<double>(3, 1.0)), Error);  // one norm per wavelet
  }
}

TEST(Compress, ThresholdKeepsExactlyTheWaveletsAboveIt) {
  for (const Case& k : kCases) {
    SCOPED_TRACE(k.name);
    const Hierarchy h = detailed(k.asset, k.scheme, k.levels);
    const Compressor c(h);
    const double diagonal = bbox_diagonal(synthesize(h, h.finest_level()));
    EXPECT_DOUBLE_EQ(c.diagonal(), diagonal);
    // Independently: |w| 2^(-j dim / 2) (sqrt2: 2^(-j / 2)), the L2 norm of a level-j wavelet.
    const double per_level = k.scheme == Scheme::Sqrt2 ? 1.0 : double(h.levels.front().dim);
    std::vector<double> magnitude;  // by fine vertex v - nv_0
    for (std::uint32_t v = h.num_vertices(0); v < h.num_vertices(h.finest_level()); ++v) {
      const double* w = &h.coeffs[3 * std::size_t(v)];
      magnitude.push_back(std::hypot(w[0], w[1], w[2]) * std::pow(2.0, -0.5 * level_of(h, v) * per_level));
    }
    std::vector<double> sorted = magnitude;
    std::sort(sorted.begin(), sorted.end());
    // Thresholds between the 10%, 50% and 90% quantiles and their neighbours.
    for (const double q : {0.1, 0.5, 0.9}) {
      const std::size_t at = static_cast<std::size_t>(q * double(sorted.size()));
      const double t = 0.5 * (sorted[at] + sorted[at + 1]) / diagonal;
      const std::vector<double> kept = c.coefficients(c.count_for_threshold(t));
      std::size_t expect_kept = 0;
      for (std::uint32_t v = h.num_vertices(0); v < h.num_vertices(h.finest_level()); ++v) {
        const double* w = &h.coeffs[3 * std::size_t(v)];
        const double m = magnitude[v - h.num_vertices(0)];
        const bool keep = m >= t * diagonal;
        expect_kept += keep;
        if (std::abs(m - t * diagonal) < 1e-12 * diagonal) continue;  // a tie within round-off
        const double* got = &kept[3 * std::size_t(v)];
        if (keep) {
          EXPECT_TRUE(got[0] == w[0] && got[1] == w[1] && got[2] == w[2]) << "wavelet " << v << " dropped at T " << t;
        } else {
          EXPECT_TRUE(got[0] == 0 && got[1] == 0 && got[2] == 0) << "wavelet " << v << " kept at T " << t;
        }
      }
      EXPECT_EQ(c.count_for_threshold(t), expect_kept);
      EXPECT_GT(expect_kept, 0u);
      EXPECT_LT(expect_kept, c.total());
    }
    EXPECT_EQ(c.count_for_threshold(0.0), c.total());
    EXPECT_THROW(c.count_for_threshold(-1.0), Error);
  }
}

TEST(Compress, LinfRespectsTheBoundAndOneMoreRemovalBreaksIt) {
  for (const Case& k : kCases) {
    SCOPED_TRACE(k.name);
    const Hierarchy h = detailed(k.asset, k.scheme, k.levels);
    const Compressor c(h);
    const double at_zero = c.evaluate(0).linf_error;
    for (const double e : {0.05 * at_zero, 0.3 * at_zero, 0.7 * at_zero}) {
      const std::size_t n = c.count_for_linf(e);
      const Compression r = c.evaluate(n);
      EXPECT_LE(r.linf_error, e);
      ASSERT_GT(n, 0u);
      EXPECT_GT(c.evaluate(n - 1).linf_error, e) << "one more removal along the ranking still keeps the bound";
      EXPECT_EQ(c.run(CompressMode::Linf, e).kept, r.kept);
    }
    EXPECT_EQ(c.count_for_linf(at_zero), 0u);  // the bound holds with nothing kept
    EXPECT_EQ(c.evaluate(c.count_for_linf(0.0)).linf_error, 0.0);
    EXPECT_THROW(c.count_for_linf(-1e-3), Error);
  }
}

TEST(Compress, RegionLeavesWaveletsOutsideUntouchedBitForBit) {
  for (const Case& k : kCases) {
    SCOPED_TRACE(k.name);
    const Hierarchy h = detailed(k.asset, k.scheme, k.levels);
    const std::vector<double> fine = synthesize(h, h.finest_level());
    const auto box = bounding_box(fine.data(), fine.size() / 3);
    // A sphere around the bounding box's upper corner region: part of the shape inside.
    Region region;
    region.kind = Region::Kind::Sphere;
    for (std::size_t a = 0; a < 3; ++a) region.centre[a] = box[1][a];
    region.radius = 0.6 * bbox_diagonal(fine);
    CompressOptions options;
    options.region = region;
    const Compressor c(h, options);
    ASSERT_GT(c.candidates(), 0u);
    ASSERT_LT(c.candidates(), c.total());
    for (const double f : {0.0, 0.3}) {
      const Compression r = c.evaluate(c.count_for_fraction(f));
      EXPECT_EQ(r.kept, c.total() - c.candidates() + static_cast<std::size_t>(std::llround(f * double(c.candidates()))));
      // Scaling coefficients are never touched.
      EXPECT_EQ(std::memcmp(r.coeffs.data(), h.coeffs.data(), 3 * h.num_vertices(0) * sizeof(double)), 0);
      std::size_t inside = 0;
      for (int j = 0; j < h.finest_level(); ++j) {
        // Where a level-j wavelet lives: its vertex on level j+1, synthesised independently.
        const std::vector<double> net = synthesize(h, j + 1);
        for (std::uint32_t v = h.num_vertices(j); v < h.num_vertices(j + 1); ++v) {
          const double* w = &h.coeffs[3 * std::size_t(v)];
          const double* got = &r.coeffs[3 * std::size_t(v)];
          const double* p = &net[3 * std::size_t(v)];
          const double d = std::hypot(p[0] - region.centre[0], p[1] - region.centre[1], p[2] - region.centre[2]);
          if (d > region.radius) {
            EXPECT_EQ(std::memcmp(got, w, 3 * sizeof(double)), 0) << "wavelet " << v << " outside changed";
          } else {
            ++inside;
            const bool zero = got[0] == 0 && got[1] == 0 && got[2] == 0;
            EXPECT_TRUE(zero || std::memcmp(got, w, 3 * sizeof(double)) == 0) << v;
            if (f == 0.0) {
              EXPECT_TRUE(zero) << "wavelet " << v << " inside kept at fraction 0";
            }
          }
        }
      }
      EXPECT_EQ(inside, c.candidates());
    }
  }
}

TEST(Compress, RawMagnitudeRanksDifferentlyOnAMultiLevelHierarchy) {
  const Hierarchy h = detailed("torus_quad.obj", Scheme::Cubic, 3);
  const Compressor normalised(h);
  CompressOptions raw_options;
  raw_options.normalise = false;
  const Compressor raw(h, raw_options);
  ASSERT_EQ(normalised.candidates(), raw.candidates());
  EXPECT_FALSE(std::equal(normalised.order().begin(), normalised.order().end(), raw.order().begin()));
  // Raw: sorted by the plain Euclidean norm of the coefficient vector.
  for (std::size_t k = 0; k < raw.candidates(); ++k) {
    const double* w = &h.coeffs[3 * std::size_t(raw.order()[k])];
    EXPECT_NEAR(raw.magnitudes()[k], std::hypot(w[0], w[1], w[2]), 1e-15 * (1 + raw.magnitudes()[k]));
  }
  // The difference shows in the levels kept: the raw ranking keeps finer wavelets (their size
  // is not weighed down by 2^(-j) for their smaller support).
  const std::size_t n = normalised.count_for_fraction(0.2);
  auto level_sum = [&](const Compressor& c) {
    std::size_t sum = 0;
    for (std::size_t k = 0; k < n; ++k) sum += static_cast<std::size_t>(level_of(h, c.order()[k]));
    return sum;
  };
  EXPECT_GT(level_sum(raw), level_sum(normalised));
}

TEST(Compress, UsesTheHierarchysExactWaveletNormsWhenItHasThem) {
  Hierarchy h = detailed("torus_quad.obj", Scheme::Linear, 2);
  const std::vector<double> area = wavelet_l2_norms(h);
  ASSERT_EQ(area.size(), h.num_vertices(2) - h.num_vertices(0));
  EXPECT_EQ(area.front(), 1.0);   // level 0
  EXPECT_EQ(area.back(), 0.5);    // level 1 of a surface: 2^(-1 * 2 / 2)
  // Norms that favour exactly one wavelet put it first.
  h.wavelet_norms.assign(area.size(), 1e-6);
  const std::uint32_t favourite = h.num_vertices(1) + 5;
  h.wavelet_norms[favourite - h.num_vertices(0)] = 1e6;
  const Compressor c(h);
  EXPECT_EQ(c.order().front(), favourite);
  EXPECT_EQ(wavelet_l2_norms(h), h.wavelet_norms);
  h.wavelet_norms.pop_back();
  EXPECT_THROW(wavelet_l2_norms(h), Error);
  EXPECT_THROW(Compressor{h}, Error);
}

TEST(Compress, GainsGiveTheSessionsShapeAndScaleTheRanking) {
  const Hierarchy h = detailed("torus_quad.obj", Scheme::Cubic, 3);
  const std::vector<double> gains{1.0, 0.5, 2.0};
  const Session session(h, gains);
  CompressOptions options;
  options.gains = gains;
  const Compressor c(h, options);
  const auto shown = session.positions(3);
  ASSERT_EQ(c.reference().size(), shown.size());
  for (std::size_t i = 0; i < shown.size(); ++i) EXPECT_NEAR(c.reference()[i], shown[i], 1e-12);
  // Stored coefficients come back without gains, only the removed ones zero.
  const std::vector<double> coeffs = c.coefficients(c.candidates());
  EXPECT_EQ(coeffs, h.coeffs);
  EXPECT_EQ(c.evaluate(c.candidates()).l2_error, 0.0);
  options.gains = {1.0, 2.0};
  EXPECT_THROW(Compressor(h, options), Error);
}

TEST(Compress, ErrorsAndThresholdsAreScaleFree) {
  Hierarchy h = detailed("torus_quad.obj", Scheme::Sqrt2, 4);
  Hierarchy big = h;
  for (double& x : big.coeffs) x *= 1000.0;
  const Compressor a(h), b(big);
  EXPECT_EQ(a.count_for_threshold(1e-3), b.count_for_threshold(1e-3));
  const Compression ra = a.evaluate(a.count_for_fraction(0.1)), rb = b.evaluate(b.count_for_fraction(0.1));
  EXPECT_NEAR(ra.l2_error, rb.l2_error, 1e-12);
  EXPECT_NEAR(ra.linf_error, rb.linf_error, 1e-12);
}

TEST(Compress, ParsesRegions) {
  const Region box = parse_region("box:1,2,3,-1,0,0.5");
  EXPECT_EQ(box.kind, Region::Kind::Box);
  EXPECT_EQ(box.lo, (std::array<double, 3>{-1, 0, 0.5}));
  EXPECT_EQ(box.hi, (std::array<double, 3>{1, 2, 3}));
  const double in[3] = {0, 1, 1}, out[3] = {0, 1, 4};
  EXPECT_TRUE(box.contains(in));
  EXPECT_FALSE(box.contains(out));
  const Region s = parse_region("sphere:0,0,0,2");
  EXPECT_EQ(s.kind, Region::Kind::Sphere);
  EXPECT_TRUE(s.contains(in));
  EXPECT_FALSE(s.contains(out));
  for (const char* bad : {"box:1,2,3", "sphere:0,0,0,-1", "cube:0,0,0,1", "sphere:0,0,x,1", "box", "sphere:0,0,0,1,"})
    EXPECT_THROW(parse_region(bad), Error) << bad;
  const Hierarchy h = detailed("torus_quad.obj", Scheme::Linear, 1);
  EXPECT_THROW(Compressor(h).count_for_fraction(1.5), Error);
  EXPECT_EQ(compress_mode_name(CompressMode::Linf), "linf");
}

// Issue 20: channel groups. A hierarchy with x, y, z and two attribute channels (a colour-like
// pair with detail of its own): the position group ranks, keeps and measures exactly as the same
// shape without the attributes, leaves the attribute channels bit for bit, and the attribute
// group is ranked by its own magnitude and measured in its own range.
TEST(Compress, ChannelGroupsRankAndMeasureOnTheirOwn) {
  const Hierarchy xyz = detailed("torus_quad.obj", Scheme::Cubic, 2);
  Hierarchy five = make_hierarchy(xyz.levels.front(), 2, Scheme::Cubic, 5);
  const std::size_t n = xyz.coeffs.size() / 3;
  for (std::size_t v = 0; v < n; ++v) {
    std::copy_n(&xyz.coeffs[3 * v], 3, &five.coeffs[5 * v]);
    // Attribute values in their own units (hundreds), with detail unlike the positions'.
    five.coeffs[5 * v + 3] = 100.0 * std::sin(0.37 * double(v));
    five.coeffs[5 * v + 4] = 50.0 * std::cos(0.11 * double(v * v % 97));
  }
  CompressOptions positions;
  positions.channels = {0, 3};
  const Compressor a(five, positions), b(xyz);
  ASSERT_EQ(std::vector<std::uint32_t>(a.order().begin(), a.order().end()), std::vector<std::uint32_t>(b.order().begin(), b.order().end()));
  for (const double keep : {0.05, 0.3}) {
    const Compression ca = a.run(CompressMode::Keep, keep), cb = b.run(CompressMode::Keep, keep);
    EXPECT_EQ(ca.kept, cb.kept);
    EXPECT_EQ(ca.l2_error, cb.l2_error);
    EXPECT_EQ(ca.linf_error, cb.linf_error);
    for (std::size_t v = 0; v < n; ++v) {
      for (int k = 0; k < 3; ++k) ASSERT_EQ(ca.coeffs[5 * v + k], cb.coeffs[3 * v + k]);
      for (int k = 3; k < 5; ++k) ASSERT_EQ(ca.coeffs[5 * v + k], five.coeffs[5 * v + k]) << "an attribute channel changed";
    }
  }
  CompressOptions attrs;
  attrs.channels = {3, 2};
  const Compressor c(five, attrs);
  // Its ranking: |(w3, w4)| x ||psi||, recomputed here.
  const std::vector<double> norms = wavelet_l2_norms(five);
  const std::uint32_t nv0 = five.num_vertices(0);
  for (std::size_t k = 0; k + 1 < c.order().size(); ++k) {
    const auto mag = [&](std::uint32_t v) { return std::hypot(five.coeffs[5 * v + 3], five.coeffs[5 * v + 4]) * norms[v - nv0]; };
    ASSERT_GE(mag(c.order()[k]), mag(c.order()[k + 1]));
  }
  EXPECT_NE(std::vector<std::uint32_t>(c.order().begin(), c.order().end()), std::vector<std::uint32_t>(a.order().begin(), a.order().end()));
  const Compression cc = c.run(CompressMode::Keep, 0.2);
  for (std::size_t v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k) ASSERT_EQ(cc.coeffs[5 * v + k], five.coeffs[5 * v + k]) << "a position channel changed";
  // Errors relative to the attributes' own range: the same at ten times the values.
  Hierarchy scaled = five;
  for (std::size_t v = 0; v < n; ++v) scaled.coeffs[5 * v + 3] *= 10, scaled.coeffs[5 * v + 4] *= 10;
  const Compression cs = Compressor(scaled, attrs).run(CompressMode::Keep, 0.2);
  EXPECT_NEAR(cs.l2_error, cc.l2_error, 1e-12);
  EXPECT_GT(cc.l2_error, 0.0);
  EXPECT_THROW(Compressor(five, CompressOptions{true, std::nullopt, {}, {4, 2}}), Error);
}
