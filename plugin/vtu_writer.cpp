// vtu_writer: the results' ParaView file (.vtu) for P1 fields, written from the coefficient arrays
// (built by `make` with ff-c++, loaded by include/model.idp).
//
// Why: FreeFEM's savevtk (iovtk) evaluates each field through its finite-element machinery, cell
// by cell: 2.75 s for the 3D Hertz sphere's 391k tetrahedra (201k dofs), against 0.2 s here, where
// the values are already one per vertex (P1 displacement) or one per element (P0 fields).
//
// writeVtu(file, Th, U, cellData, names): Th a 2D mesh or a mesh3; U the displacement's dof vector
// in the numbering of [P1, P1] or [P1, P1, P1] (dof d v + c), written as the point field
// "displacement" with 3 components (0 out of plane); cellData the P0 arrays one after the other
// (nt values each), written as cell fields named by the space-separated `names`; a name written
// "point:NAME" is a point field NAME instead, its nv values after all the cell fields' (the fluid
// pressure on a seal's wetted surface lives on vertices, not elements). The layout is
// savevtk's: XML UnstructuredGrid, inline base64 "binary" arrays each led by its 4-byte length,
// Float32 values, the element cells only (triangles, VTK type 5, or tetrahedra, type 10).
// scripts/vtu.py reads it for the report's figures. Returns the number of cells, or minus the errno
// of a write that failed (a full disk): the script says so (include/model.idp). Under MPI only
// process 0 writes: the others return the number of cells and write nothing.
#include "ff++.hpp"
#include "AFunction_ext.hpp"
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

extern long mpirank;   // FreeFEM's: 0 under FreeFem++

namespace {

// base64 of the 4-byte little-endian length followed by the bytes
std::string base64Block(const void *data, uint32_t bytes) {
  static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> in(4 + size_t(bytes));
  for (int b = 0; b < 4; b++) in[b] = (unsigned char)((bytes >> (8 * b)) & 0xff);
  const unsigned char *source = static_cast<const unsigned char *>(data);
  std::copy(source, source + bytes, in.begin() + 4);
  std::string out;
  out.reserve((in.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    uint32_t v = (uint32_t(in[i]) << 16) | (uint32_t(in[i + 1]) << 8) | in[i + 2];
    out += alphabet[(v >> 18) & 63]; out += alphabet[(v >> 12) & 63]; out += alphabet[(v >> 6) & 63]; out += alphabet[v & 63];
  }
  if (i < in.size()) {
    uint32_t v = uint32_t(in[i]) << 16;
    if (i + 1 < in.size()) v |= uint32_t(in[i + 1]) << 8;
    out += alphabet[(v >> 18) & 63]; out += alphabet[(v >> 12) & 63];
    out += (i + 1 < in.size()) ? alphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

template <class T>
void dataArray(FILE *f, const char *type, const std::string &name, int components, const std::vector<T> &values) {
  std::fprintf(f, "<DataArray type=\"%s\"%s%s%s NumberOfComponents=\"%d\" format=\"binary\">\n", type,
               name.empty() ? "" : " Name=\"", name.c_str(), name.empty() ? "" : "\"", components);
  std::string text = base64Block(values.data(), uint32_t(values.size() * sizeof(T)));
  std::fputs(text.c_str(), f);
  std::fputs("\n</DataArray>\n", f);
}

// the mesh's vertices, elements (d + 1 vertex numbers each) and the fields, written to file
long writeFile(const std::string &file, long nv, long nt, int d, const std::vector<float> &points,
           const std::vector<int32_t> &connectivity, const KN<double> &U, const KN<double> &cellData,
           const std::string &names) {
  std::vector<std::string> fields, pointFields;
  std::istringstream words(names);
  const std::string pointTag = "point:";
  for (std::string w; words >> w;) {
    if (w.compare(0, pointTag.size(), pointTag) == 0) pointFields.push_back(w.substr(pointTag.size()));
    else fields.push_back(w);
  }
  long cellValues = long(fields.size()) * nt;
  if (U.N() != d * nv || cellData.N() != cellValues + long(pointFields.size()) * nv) {
    std::cout << "error: writeVtu: " << U.N() << " displacement values for " << nv << " vertices in " << d
              << "D, or " << cellData.N() << " field values for " << fields.size() << " cell fields on " << nt
              << " elements and " << pointFields.size() << " point fields on " << nv << " vertices" << std::endl;
    std::exit(2);
  }
  FILE *f = std::fopen(file.c_str(), "w");
  if (!f) return -long(errno ? errno : EIO);
  std::fprintf(f, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" byte_order=\"LittleEndian\">\n");
  std::fprintf(f, "<UnstructuredGrid>\n<Piece NumberOfPoints=\"%ld\" NumberOfCells=\"%ld\">\n<Points>\n", nv, nt);
  dataArray(f, "Float32", "", 3, points);
  std::fprintf(f, "</Points>\n<Cells>\n");
  dataArray(f, "Int32", "connectivity", 1, connectivity);
  std::vector<int32_t> offsets(nt);
  for (long k = 0; k < nt; k++) offsets[k] = int32_t((k + 1) * (d + 1));
  dataArray(f, "Int32", "offsets", 1, offsets);
  std::vector<uint8_t> types(nt, uint8_t(d == 3 ? 10 : 5));
  dataArray(f, "UInt8", "types", 1, types);
  std::fprintf(f, "</Cells>\n<PointData>\n");
  std::vector<float> displacement(3 * nv, 0.f);
  for (long v = 0; v < nv; v++)
    for (int c = 0; c < d; c++) displacement[3 * v + c] = float(U[d * v + c]);
  dataArray(f, "Float32", "displacement", 3, displacement);
  std::vector<float> pointValues(nv);
  for (size_t m = 0; m < pointFields.size(); m++) {
    for (long v = 0; v < nv; v++) pointValues[v] = float(cellData[cellValues + long(m) * nv + v]);
    dataArray(f, "Float32", pointFields[m], 1, pointValues);
  }
  std::fprintf(f, "</PointData>\n<CellData>\n");
  std::vector<float> values(nt);
  for (size_t m = 0; m < fields.size(); m++) {
    for (long k = 0; k < nt; k++) values[k] = float(cellData[long(m) * nt + k]);
    dataArray(f, "Float32", fields[m], 1, values);
  }
  std::fprintf(f, "</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
  bool failed = std::fflush(f) != 0 || std::ferror(f);
  int error = errno;
  if (std::fclose(f) != 0 && !failed) { failed = true; error = errno; }
  if (failed) return -long(error ? error : EIO);
  return nt;
}

// the vertices' coordinates (z = 0 in 2D) and the elements' vertex numbers of a P1 mesh of dimension d
double zOf(const Mesh::Vertex &) { return 0.; }
double zOf(const Vertex3 &v) { return v.z; }
template <class MeshType, int d>
long writeVtuOf(string *const &file, const MeshType *pTh, KN<double> *const &pU, KN<double> *const &pCells,
                string *const &names) {
  ffassert(pTh);
  const MeshType &Th = *pTh;
  if (mpirank != 0) return Th.nt;
  std::vector<float> points(3 * Th.nv);
  for (long v = 0; v < Th.nv; v++) {
    points[3 * v] = float(Th(v).x); points[3 * v + 1] = float(Th(v).y); points[3 * v + 2] = float(zOf(Th(v)));
  }
  std::vector<int32_t> connectivity((d + 1) * Th.nt);
  for (long k = 0; k < Th.nt; k++)
    for (int a = 0; a <= d; a++) connectivity[(d + 1) * k + a] = int32_t(Th(Th[k][a]));
  return writeFile(*file, Th.nv, Th.nt, d, points, connectivity, *pU, *pCells, *names);
}
long writeVtu2D(string *const &file, pmesh const &pTh, KN<double> *const &pU, KN<double> *const &pCells, string *const &names) {
  return writeVtuOf<Mesh, 2>(file, pTh, pU, pCells, names);
}
long writeVtu3D(string *const &file, pmesh3 const &pTh, KN<double> *const &pU, KN<double> *const &pCells, string *const &names) {
  return writeVtuOf<Mesh3, 3>(file, pTh, pU, pCells, names);
}

void init() {
  Global.Add("writeVtu", "(", new OneOperator5_<long, string *, pmesh, KN<double> *, KN<double> *, string *>(writeVtu2D));
  Global.Add("writeVtu", "(", new OneOperator5_<long, string *, pmesh3, KN<double> *, KN<double> *, string *>(writeVtu3D));
}

}  // namespace

LOADFUNC(init)
