// msh_loader: gmsh's ASCII msh 2.2 files read into a FreeFEM mesh3 (built by `make` with ff-c++,
// loaded by include/mesh/gmsh_mesh.idp), in place of the gmsh plugin's gmshload3.
//
// Why: FreeFEM builds a tetrahedral mesh's face adjacency with a hash table of nv buckets keyed
// by v0 * rotl(v1, 7) * rotl(v2, 14) (HashTable.hpp, SortArray<int, 3>): for vertex numbers below
// 2^50 that key is a multiple of 2^21, so when nv is divisible by 2^k only nv / 2^k buckets are
// ever used and every face search walks chains 2^k times longer. The 3D Hertz sphere at 201k
// dofs: gmshload3 took 1.9 s with nv = 67121 and 12.6 s with nv = 67120 = 2^4 * 4195 (measured on
// the same mesh, one tetrahedron split). gmsh's node count is whatever the Delaunay refinement
// gives, so the loader makes it odd: when nv is even, the tetrahedron of largest volume is
// split into four at its centroid (one vertex more, the same geometry and boundary; the split
// element is the coarsest, far from where the sizes are set by a contact zone).
//
// loadMsh3(file, split): the mesh3 of the file's tetrahedra (type 4) and boundary triangles
// (type 2), labelled by their first tag (the physical group) as gmshload3 does; the other
// element types gmsh writes for a 3D mesh (points 15, lines 1) are skipped. split = 0 keeps
// the file's vertices as they are. Prints one line when it splits. A file it cannot read ends
// the run with "error: ..." and exit code 2 (the suite's bad-input code).
//
// mshProblem(file, dim, size): why an ASCII msh 2.2 file given by a user (-mesh) cannot be used as
// a mesh of dimension dim for a body of the given size, or "" when it can, before FreeFEM's readers
// see it (gmshload ends in an assertion or reads out of bounds on a corrupt file): the format, the
// sections and their counts, finite coordinates, no repeated node number, every element's nodes
// present, only point, line, triangle (and in 3D tetrahedron) elements, at least one element of the
// dimension and one of its boundary, no element of the dimension with a zero area or volume (below
// 1e-12 of the bounding box's) or turned inside out (a clockwise triangle ended in FreeFEM's
// "Assertion fail: (area > 0)"; an inverted tetrahedron reached the solver), and the bounding box's
// largest side within a factor 2 of size (a mesh in other units, 1000 times too large, reached the
// solver, exit 3).
#include "ff++.hpp"
#include "AFunction_ext.hpp"
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

// A file that cannot be read as a mesh: thrown by the parser, caught by the two entry points.
struct MshError {
  std::string what;
};

[[noreturn]] void refuse(const std::string &file, const std::string &what) {
  (void)file;
  throw MshError{what};
}

[[noreturn]] void exitWith(const std::string &file, const std::string &what) {
  std::cout << "error: mesh file '" << file << "': " << what << std::endl;
  std::cout.flush();
  std::exit(2);
}

// The whole file, parsed by a cursor that skips white space before each number.
struct Reader {
  std::string file;
  std::vector<char> text;
  const char *p, *end;
  explicit Reader(const std::string &name) : file(name) {
    FILE *f = std::fopen(name.c_str(), "rb");
    if (!f) refuse(file, "cannot be opened");
    std::fseek(f, 0, SEEK_END);
    long size = std::ftell(f);
    std::fseek(f, 0, SEEK_SET);
    text.resize(size + 1);
    if (size > 0 && std::fread(text.data(), 1, size, f) != size_t(size)) refuse(file, "cannot be read");
    std::fclose(f);
    text[size] = '\0';
    p = text.data();
    end = p + size;
  }
  // moves past the line "$name"; false when there is none
  bool section(const char *name) {
    std::string marker = std::string("$") + name;
    for (const char *q = text.data(); q < end; q++) {
      if ((q == text.data() || q[-1] == '\n') && std::strncmp(q, marker.c_str(), marker.size()) == 0) {
        p = q + marker.size();
        return true;
      }
    }
    return false;
  }
  long integer() {
    char *next;
    errno = 0;
    long value = std::strtol(p, &next, 10);
    if (next == p || errno) refuse(file, "an integer was expected");
    p = next;
    return value;
  }
  double real() {
    char *next;
    double value = std::strtod(p, &next);
    if (next == p) refuse(file, "a number was expected");
    p = next;
    return value;
  }
};

// vertices of gmsh's first-order element types (0: a type this loader does not read)
int elementVertices(long type) {
  switch (type) {
    case 1: return 2;
    case 2: return 3;
    case 4: return 4;
    case 15: return 1;
    default: return 0;
  }
}

double signedVolume(const std::vector<double> &xyz, const int *v) {
  const double *a = &xyz[3 * v[0]], *b = &xyz[3 * v[1]], *c = &xyz[3 * v[2]], *d = &xyz[3 * v[3]];
  double b0 = b[0] - a[0], b1 = b[1] - a[1], b2 = b[2] - a[2];
  double c0 = c[0] - a[0], c1 = c[1] - a[1], c2 = c[2] - a[2];
  double d0 = d[0] - a[0], d1 = d[1] - a[1], d2 = d[2] - a[2];
  return (b0 * (c1 * d2 - c2 * d1) - b1 * (c0 * d2 - c2 * d0) + b2 * (c0 * d1 - c1 * d0)) / 6;
}

pmesh3 readMsh3(Stack stack, string *const &fileName, const long &split) {
  Reader in(*fileName);
  if (!in.section("MeshFormat")) refuse(in.file, "no $MeshFormat section (gmsh -format msh22)");
  double version = in.real();
  long binary = in.integer();
  in.integer();
  if (version < 2 || version >= 3 || binary != 0) refuse(in.file, "not an ASCII msh 2.2 file (gmsh -format msh22)");

  if (!in.section("Nodes")) refuse(in.file, "no $Nodes section");
  long nv = in.integer();
  if (nv <= 0) refuse(in.file, "no nodes");
  std::vector<double> xyz(3 * nv);
  std::vector<long> tags(nv);
  long largestTag = 0;
  for (long i = 0; i < nv; i++) {
    tags[i] = in.integer();
    if (tags[i] <= 0) refuse(in.file, "a node number is not positive");
    largestTag = std::max(largestTag, tags[i]);
    for (int c = 0; c < 3; c++) xyz[3 * i + c] = in.real();
  }
  std::vector<int> vertexOf(largestTag + 1, -1);
  for (long i = 0; i < nv; i++) vertexOf[tags[i]] = int(i);

  if (!in.section("Elements")) refuse(in.file, "no $Elements section");
  long count = in.integer();
  std::vector<int> tets, triangles;   // 4 or 3 vertex numbers, then the label
  for (long e = 0; e < count; e++) {
    in.integer();
    long type = in.integer(), ntags = in.integer();
    int n = elementVertices(type);
    if (n == 0) refuse(in.file, "element type " + std::to_string(type) + " (only points, lines, triangles and tetrahedra)");
    long label = 0;
    for (long t = 0; t < ntags; t++) {
      long tag = in.integer();
      if (t == 0) label = tag;
    }
    int v[4];
    for (int k = 0; k < n; k++) {
      long node = in.integer();
      if (node <= 0 || node > largestTag || vertexOf[node] < 0) refuse(in.file, "an element refers to a missing node");
      v[k] = vertexOf[node];
    }
    std::vector<int> &list = (type == 4 ? tets : triangles);
    if (type == 4 || type == 2) {
      list.insert(list.end(), v, v + n);
      list.push_back(int(label));
    }
  }
  long nt = long(tets.size() / 5), nbe = long(triangles.size() / 4);
  if (nt == 0) refuse(in.file, "no tetrahedra");

  long vertices = nv;
  if (split && nv % 2 == 0) {
    long largest = 0;
    double largestVolume = -1;
    for (long k = 0; k < nt; k++) {
      double volume = std::fabs(signedVolume(xyz, &tets[5 * k]));
      if (volume > largestVolume) { largestVolume = volume; largest = k; }
    }
    int centre = int(nv);
    for (int c = 0; c < 3; c++) {
      double sum = 0;
      for (int k = 0; k < 4; k++) sum += xyz[3 * tets[5 * largest + k] + c];
      xyz.push_back(sum / 4);
    }
    // each corner replaced by the centre in turn: four tetrahedra of the parent's orientation
    int parent[5];
    std::copy(&tets[5 * largest], &tets[5 * largest] + 5, parent);
    for (int r = 0; r < 4; r++) {
      int *child = (r == 0 ? &tets[5 * largest] : nullptr);
      int corners[5];
      std::copy(parent, parent + 5, corners);
      corners[r] = centre;
      if (child) std::copy(corners, corners + 5, child);
      else tets.insert(tets.end(), corners, corners + 5);
    }
    vertices = nv + 1;
    nt += 3;
    std::cout << "  " << *fileName << ": " << nv << " vertices, an even number: the largest tetrahedron ("
              << largestVolume << ") split at its centroid, " << vertices
              << " vertices (FreeFEM's face hash uses nv / 2^k buckets when 2^k divides nv)" << std::endl;
  }

  Vertex3 *v = new Vertex3[vertices];
  for (long i = 0; i < vertices; i++) {
    v[i].x = xyz[3 * i];
    v[i].y = xyz[3 * i + 1];
    v[i].z = xyz[3 * i + 2];
    v[i].lab = 1;
  }
  Tet *t = new Tet[nt];
  for (long k = 0; k < nt; k++) t[k].set(v, &tets[5 * k], tets[5 * k + 4]);
  Triangle3 *b = new Triangle3[nbe];
  for (long k = 0; k < nbe; k++) b[k].set(v, &triangles[4 * k], triangles[4 * k + 3]);
  Mesh3 *Th = new Mesh3(int(vertices), int(nt), int(nbe), v, t, b, true, false);   // gmshload3's defaults
  Th->BuildGTree();
  Add2StackOfPtr2FreeRC(stack, Th);
  return Th;
}

pmesh3 loadMsh3(Stack stack, string *const &fileName, const long &split) {
  try {
    return readMsh3(stack, fileName, split);
  } catch (const MshError &e) {
    exitWith(*fileName, e.what);
  }
}

std::string mshCheck(const std::string &file, long dim, double bodySize) {
  Reader in(file);
  if (!in.section("MeshFormat")) refuse(file, "no $MeshFormat section (gmsh -format msh22)");
  double version = in.real();
  long binary = in.integer();
  in.integer();
  if (version < 2 || version >= 3 || binary != 0) refuse(file, "not an ASCII msh 2.2 file (gmsh -format msh22)");
  if (!in.section("Nodes")) refuse(file, "no $Nodes section");
  long nv = in.integer();
  if (nv <= 0 || nv > 100000000) refuse(file, "no nodes, or an impossible node count");
  std::vector<double> xyz(3 * nv);
  std::vector<long> tags(nv);
  long largestTag = 0;
  double low[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, high[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (long i = 0; i < nv; i++) {
    tags[i] = in.integer();
    if (tags[i] <= 0 || tags[i] > 1000000000) refuse(file, "node number " + std::to_string(tags[i]) + " is out of range");
    largestTag = std::max(largestTag, tags[i]);
    for (int c = 0; c < 3; c++) {
      xyz[3 * i + c] = in.real();
      if (!std::isfinite(xyz[3 * i + c])) refuse(file, "node " + std::to_string(tags[i]) + " has a coordinate that is not a finite number");
      low[c] = std::min(low[c], xyz[3 * i + c]);
      high[c] = std::max(high[c], xyz[3 * i + c]);
    }
  }
  std::vector<long> vertexOf(largestTag + 1, -1);
  for (long i = 0; i < nv; i++) {
    if (vertexOf[tags[i]] >= 0) refuse(file, "node number " + std::to_string(tags[i]) + " is given twice");
    vertexOf[tags[i]] = i;
  }
  if (!in.section("Elements")) refuse(file, "no $Elements section");
  long count = in.integer();
  if (count <= 0) refuse(file, "no elements");
  double size = 0;
  for (int c = 0; c < 3; c++) size = std::max(size, high[c] - low[c]);
  long volumes = 0, boundaries = 0;
  const long volumeType = dim == 3 ? 4 : 2, boundaryType = dim == 3 ? 2 : 1;
  for (long e = 0; e < count; e++) {
    long number = in.integer();
    long type = in.integer(), ntags = in.integer();
    int n = elementVertices(type);
    if (n == 0 || (dim == 2 && type == 4)) refuse(file, "element " + std::to_string(number) + " has type " + std::to_string(type)
                                                   + (dim == 2 ? " (a 2D mesh: points, lines and triangles)" : " (points, lines, triangles, tetrahedra)"));
    if (ntags < 0 || ntags > 100) refuse(file, "element " + std::to_string(number) + " has an impossible tag count");
    for (long t = 0; t < ntags; t++) in.integer();
    long v[4];
    for (int k = 0; k < n; k++) {
      long node = in.integer();
      if (node <= 0 || node > largestTag || vertexOf[node] < 0)
        refuse(file, "element " + std::to_string(number) + " refers to node " + std::to_string(node) + ", which is not in $Nodes");
      v[k] = vertexOf[node];
    }
    if (type == boundaryType) boundaries++;
    if (type == volumeType) {
      volumes++;
      double measure;
      if (dim == 3) {
        int w[4] = {int(v[0]), int(v[1]), int(v[2]), int(v[3])};
        measure = signedVolume(xyz, w);
      } else {
        const double *a = &xyz[3 * v[0]], *b = &xyz[3 * v[1]], *c = &xyz[3 * v[2]];
        measure = 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
      }
      std::string element = "element " + std::to_string(number);
      if (!(std::fabs(measure) > 1e-12 * std::pow(size, double(dim))))
        refuse(file, element + " is degenerate (" + (dim == 3 ? "zero volume" : "zero area") + ")");
      if (measure < 0)
        refuse(file, element + (dim == 3
                                ? " is inverted (negative volume: its nodes in the wrong order)"
                                : " is clockwise (negative area): FreeFEM takes counter-clockwise"
                                  " triangles"));
    }
  }
  if (!in.section("EndElements")) refuse(file, "the $Elements section is cut short (no $EndElements)");
  if (volumes == 0) refuse(file, dim == 3 ? "no tetrahedra" : "no triangles");
  if (boundaries == 0) refuse(file, dim == 3 ? "no boundary triangles" : "no boundary lines");
  if (bodySize > 0 && !(size >= bodySize / 2 && size <= 2 * bodySize)) {
    char text[160];
    snprintf(text, sizeof text, "its bounding box's largest side, %g, is not within a factor 2 of "
             "the body's size %g (other units?)", size, bodySize);
    refuse(file, text);
  }
  return "";
}

string *mshProblem(Stack stack, string *const &fileName, const long &dim, const double &bodySize) {
  std::string why;
  try {
    why = mshCheck(*fileName, dim, bodySize);
  } catch (const MshError &e) {
    why = e.what;
  }
  return Add2StackOfPtr2Free(stack, new string(why));
}

void init() {
  Global.Add("loadMsh3", "(", new OneOperator2s_<pmesh3, string *, long>(loadMsh3));
  Global.Add("mshProblem", "(", new OneOperator3s_<string *, string *, long, double>(mshProblem));
}

}  // namespace

LOADFUNC(init)
