#pragma once
// OpenSubdiv as a peer: a uniformly refined TopologyRefiner for a polygon fixture, shared by the
// peer tests and the benchmarks so both compare against the same OpenSubdiv setup.
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <memory>
#include <vector>

#include "tests/mesh_fixtures.h"

namespace sublift::fixtures {

/// Refines `m` `levels` times with `scheme` (boundaries: edges only, i.e. smooth boundary
/// curves, the convention Sublift's features follow). Returns null if OpenSubdiv refuses `m`.
/// `full_topology`: the last level keeps its edges too (Far drops them by default).
inline std::unique_ptr<OpenSubdiv::Far::TopologyRefiner> osd_refiner(const Polygons& m, OpenSubdiv::Sdc::SchemeType scheme,
                                                                     int levels, bool full_topology = false) {
  namespace Far = OpenSubdiv::Far;
  namespace Sdc = OpenSubdiv::Sdc;
  std::vector<int> sizes(m.faces.rows());
  for (std::size_t f = 0; f < sizes.size(); ++f) sizes[f] = static_cast<int>(m.faces.size(f));
  const std::vector<Far::Index> corners(m.faces.items.begin(), m.faces.items.end());
  Far::TopologyDescriptor desc;
  desc.numVertices = static_cast<int>(m.num_vertices);
  desc.numFaces = static_cast<int>(sizes.size());
  desc.numVertsPerFace = sizes.data();
  desc.vertIndicesPerFace = corners.data();
  Sdc::Options opts;
  opts.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> r(Factory::Create(desc, Factory::Options(scheme, opts)));
  Far::TopologyRefiner::UniformOptions uniform(levels);
  uniform.fullTopologyInLastLevel = full_topology;
  if (r) r->RefineUniform(uniform);
  return r;
}

}  // namespace sublift::fixtures
