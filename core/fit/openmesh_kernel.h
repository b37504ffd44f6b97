#pragma once
// OpenMesh's mesh kernels, for every file that uses them (the fitting base's decimation, the
// peer tests against OpenMesh's subdividers). GCC 12 reports the default-constructed prototype
// that OpenMesh's add_property copies (every mesh's points property) as maybe used
// uninitialised, depending on what is inlined around it; the library never reads that value, so
// the warning is silenced for its headers alone (their first inclusion decides: include this
// before any other OpenMesh header).
#if defined(__GNUC__) && !defined(__clang__)  // (clang has no such warning)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
