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

SchemeSwitch switch_scheme(const Session& session, Scheme to) {
  const Hierarchy& old = session.hierarchy();
  const Complex& base = old.levels.front();
  check_scheme_takes(to, base);
  const int J = old.finest_level();
  SchemeSwitch out;
  if (scheme_info(to).refinement == scheme_info(old.scheme).refinement) {
    out.hierarchy = make_hierarchy(base, J, to, 3);
    analyze(out.hierarchy, session.positions(J));
    out.kept_detail = true;
  } else {
    out.hierarchy = make_hierarchy(base, level_under_scheme(J, old.scheme, to), to, 3);
    set_base(out.hierarchy, session.positions(0));
  }
  return out;
}

}  // namespace sublift
