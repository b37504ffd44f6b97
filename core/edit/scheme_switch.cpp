#include "core/edit/scheme_switch.h"

#include <algorithm>
#include <string>

#include "core/base/errors.h"

namespace sublift {

void check_scheme_takes(Scheme scheme, const Complex& base) {
  const SchemeInfo& info = scheme_info(scheme);
  if (info.surfaces_only && base.dim != 2)
    throw Error("the " + scheme_name(scheme) + " scheme refines surfaces only; this is a " +
                (base.dim == 1 ? "curve" : "volume lattice") + " (use linear or cubic)");
  if (info.triangles_only)
    for (std::uint32_t f = 0; f < base.num_faces(); ++f)
      if (base.faces.size(f) != 3)
        throw Error("the " + scheme_name(scheme) + " scheme needs a triangle mesh; face " + std::to_string(f) + " has " +
                    std::to_string(base.faces.size(f)) + " corners (use linear, cubic or sqrt2 for polygon meshes)");
}

int level_under_scheme(int level, Scheme from, Scheme to) {
  const int a = scheme_levels_per_split(from), b = scheme_levels_per_split(to);
  return std::min((level * b + a - 1) / a, max_levels(to));
}

SchemeSwitchInput scheme_switch_input(const Session& session, Scheme to) {
  const Hierarchy& old = session.hierarchy();
  check_scheme_takes(to, old.levels.front());
  SchemeSwitchInput in;
  in.base = old.levels.front();
  in.from = old.scheme;
  in.to = to;
  in.finest = old.finest_level();
  const bool same = scheme_info(to).refinement == scheme_info(old.scheme).refinement;
  const std::span<const double> net = session.positions(same ? in.finest : 0);
  in.positions.assign(net.begin(), net.end());
  return in;
}

SchemeSwitch switch_scheme(const SchemeSwitchInput& in, const SwitchProgress& progress) {
  check_scheme_takes(in.to, in.base);
  const bool same = scheme_info(in.to).refinement == scheme_info(in.from).refinement;
  const int levels = same ? in.finest : level_under_scheme(in.finest, in.from, in.to);
  // Building the levels is nearly all of the work; the analysis is a few synthesis passes.
  LevelProgress building;
  if (progress) building = [&](double f) { return progress("building the levels", 0.95 * f); };
  SchemeSwitch out;
  out.hierarchy = make_hierarchy(in.base, levels, in.to, 3, false, 0, 2, building);
  if (progress && !progress(same ? "analysing the shape" : "setting the base", 0.95))
    throw Cancelled("changing the scheme was cancelled");
  if (same) analyze(out.hierarchy, in.positions);
  else set_base(out.hierarchy, in.positions);
  out.kept_detail = same;
  return out;
}

SchemeSwitch switch_scheme(const Session& session, Scheme to) { return switch_scheme(scheme_switch_input(session, to)); }

}  // namespace sublift
