// Compression with the triangle schemes (paper 004 sec. 7.2) on a real scan resampled onto the
// octahedron: the error falls as the kept fraction grows, and ranking by |w| ||psi|| (the exact
// L2 norms of the wavelets) beats ranking by the raw magnitude |w| in L2 error at 1 % and 5 %.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "core/analysis/compress.h"
#include "core/multires/hierarchy.h"
#include "core/io/mesh/mesh_import.h"
#include "core/analysis/sphere_resample.h"

using namespace sublift;

TEST(TriCompress, NormalisedBeatsRawOnAResampledScan) {
  const std::filesystem::path scan = std::filesystem::path(SUBLIFT_SHARED_DATA) / "scans/bunny_npm_lowres.obj";
  if (!std::filesystem::exists(scan)) GTEST_SKIP() << "no third-party data at " << scan << " (SUBLIFT_SHARED_DATA)";
  const int J = 5;
  const SphereResample s = resample_sphere(import_surface_mesh(scan.string()).mesh, J);
  for (Scheme scheme : {Scheme::LinearTri, Scheme::Butterfly, Scheme::Loop}) {
    SCOPED_TRACE(scheme_name(scheme));
    Hierarchy h = make_hierarchy(octahedron_complex(), J, scheme, 3);
    analyze(h, s.positions);
    CompressOptions raw_options;
    raw_options.normalise = false;
    const Compressor normalised(h), raw(h, raw_options);
    double previous = 1e300;
    for (double f : {0.0, 0.01, 0.05, 0.2, 0.5, 1.0}) {
      const Compression c = normalised.evaluate(normalised.count_for_fraction(f));
      EXPECT_LE(c.l2_error, previous) << "fraction " << f;
      previous = c.l2_error;
      if (f == 1.0) {
        EXPECT_LT(c.l2_error, 1e-12);
      }
      {
        const Compression r = raw.evaluate(raw.count_for_fraction(f));
        std::printf("%s f=%.2f normalised %.6g raw %.6g\n", scheme_name(scheme).c_str(), f, c.l2_error, r.l2_error);
        // The sparse end, where compression is used: 1 % and 5 %. (At 20 % and 50 % Loop's raw
        // ranking is slightly better, 0.00137 against 0.00151 at 20 %: its wavelets are the least
        // orthogonal, so |w| ||psi|| predicts the error of a large removal set less well;
        // docs/compression.md.)
        if (f == 0.01 || f == 0.05) {
          EXPECT_LT(c.l2_error, r.l2_error) << "fraction " << f << ": normalised " << c.l2_error << ", raw " << r.l2_error;
        }
      }
    }
  }
}
