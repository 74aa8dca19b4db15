// vtkio.cc - store particles as VTK XML files (see vtkio.h). The one C++ file of libvres:
// VTK 9.1 has only a C++ API, so these extern "C" functions wrap it. Every entry point
// catches C++ exceptions, and VTK's own error output (vtkOutputWindow and vtkLogger, which
// would print several multi-line reports per failure) is captured and turned into one
// vres_error line naming the file.
#include "vtkio.h"

extern "C" {
#include "fileio.h"
#include "log.h"
#include "owner.h"
}

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>
#include <strings.h>
#include <vector>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTypeUInt64Array.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>
#include <vtkXMLUnstructuredGridWriter.h>

namespace {

// Field bits in the order of their names below; the order is the one files and messages use.
const unsigned field_bits[] = {VRES_VTK_DOMAIN,   VRES_VTK_TYPE,    VRES_VTK_MK,       VRES_VTK_ID,
                               VRES_VTK_VELOCITY, VRES_VTK_DENSITY, VRES_VTK_PRESSURE, VRES_VTK_MASS,
                               VRES_VTK_DP,       VRES_VTK_NORMAL};
// Array names as ParaView shows them, matching field_bits.
const char *const field_names[] = {"Domain",  "Type",     "Mk",   "Id", "Velocity",
                                   "Density", "Pressure", "Mass", "Dp", "Normal"};
const int nfields = sizeof field_bits / sizeof field_bits[0];

// An output window that keeps VTK's messages instead of printing them: errors are counted and
// the first one kept for the caller's single message; warnings go to vres_debug (-v).
class capture_window : public vtkOutputWindow {
public:
    static capture_window *New();
    vtkTypeMacro(capture_window, vtkOutputWindow);

    int nerrors = 0;   // error reports received
    std::string first; // the first error, reduced to its message line

    // Text not classified below (debug output) is dropped.
    void DisplayText(const char *) override {}
    // An error: counted, the first one kept.
    void DisplayErrorText(const char *t) override
    {
        if (nerrors++ == 0) first = message_line(t);
    }
    // A warning: shown with -v only, one line.
    void DisplayWarningText(const char *t) override { vres_debug("VTK: %s", message_line(t).c_str()); }
    // A warning from outside any VTK object: the same.
    void DisplayGenericWarningText(const char *t) override { DisplayWarningText(t); }

    // VTK reports read "ERROR: In FILE, line N\nCLASS (0xADDR): message\n\n": keep the message.
    static std::string message_line(const char *t)
    {
        std::string s(t ? t : "");
        size_t nl = s.find('\n');
        if (s.compare(0, 3, "ERR") == 0 || s.compare(0, 4, "Warn") == 0)
            s = nl == std::string::npos ? s : s.substr(nl + 1);
        size_t cut = s.find("): ");
        if (cut != std::string::npos && cut < s.find('\n')) s = s.substr(cut + 3);
        nl = s.find('\n');
        if (nl != std::string::npos) s.resize(nl);
        while (!s.empty() && (s.back() == ' ' || s.back() == '.')) s.pop_back();
        return s;
    }

protected:
    capture_window() = default;
};
vtkStandardNewMacro(capture_window);

// While alive, VTK's messages go to a capture_window; the previous output window comes back
// afterwards. vtkLogger's stderr sink, which would print each message a second time, is
// turned off for good: vres tools never want VTK's log on stderr.
class vtk_quiet {
public:
    vtk_quiet()
    {
        vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
        prev = vtkOutputWindow::GetInstance();
        vtkOutputWindow::SetInstance(cap);
    }
    ~vtk_quiet() { vtkOutputWindow::SetInstance(prev); }
    vtk_quiet(const vtk_quiet &) = delete;
    vtk_quiet &operator=(const vtk_quiet &) = delete;

    vtkNew<capture_window> cap; // the messages of this scope

private:
    vtkSmartPointer<vtkOutputWindow> prev; // window to restore
};

// Words for a VTK reader/writer error code: below FirstVTKErrorCode VTK stores errno values.
// (vtkErrorCode::GetStringFromErrorCode says the same but would pull in one more VTK library.)
const char *error_code_text(unsigned long code)
{
    switch (code) {
    case vtkErrorCode::FileNotFoundError: return "file not found";
    case vtkErrorCode::CannotOpenFileError: return "cannot open file";
    case vtkErrorCode::UnrecognizedFileTypeError: return "unrecognized file type";
    case vtkErrorCode::PrematureEndOfFileError: return "premature end of file";
    case vtkErrorCode::FileFormatError: return "file format error";
    case vtkErrorCode::NoFileNameError: return "no file name";
    case vtkErrorCode::OutOfDiskSpaceError: return "out of disk space";
    default: return code < vtkErrorCode::FirstVTKErrorCode ? strerror((int)code) : "unknown VTK error";
    }
}

// Report an exception caught at the C boundary, naming the file being handled.
void report_exception(const char *name, const char *what)
{
    vres_error("%s: %s", name, what);
}

// The particles options o write from domain k of s: show[i] = 1 for each one written (empty
// when none is). Buffer particles and those lying where another domain owns go unless
// o->buffers; other domains than o->domain go when one is picked.
std::vector<unsigned char> selection(const vres_store *s, const vres_vtk_opts *o, size_t k)
{
    const vres_domain *d = &s->dom[k];
    std::vector<unsigned char> show;
    if (o->domain >= 0 && (size_t)o->domain != k) return show;
    show.assign(d->n, 1);
    if (o->buffers) return show;
    uint8_t *own = d->pos ? vres_owner_mask(s, k) : nullptr;
    for (size_t i = 0; i < d->n; i++) {
        int type = d->type ? (int)d->type[i] : (int)VRES_FLUID;
        show[i] = type != VRES_BUFFER && (!own || own[i]);
    }
    free(own);
    return show;
}

// Give a ncomp components and n tuples. VTK reports a failed allocation (and leaves the array
// empty) instead of throwing; this throws, so the C boundary reports it once.
void size_array(vtkDataArray *a, int ncomp, vtkIdType n)
{
    a->SetNumberOfComponents(ncomp);
    a->SetNumberOfTuples(n);
    if (a->GetNumberOfTuples() != n) throw std::bad_alloc();
}

// A new point-data array of ncomp components and n tuples, named and attached to pd.
template <class A> A *new_array(vtkPointData *pd, const char *name, int ncomp, vtkIdType n)
{
    vtkNew<A> a;
    a->SetName(name);
    size_array(a, ncomp, n);
    pd->AddArray(a);
    return a; // pd holds the reference
}

// Build the grid and write it; exceptions are left to the caller.
int write_vtu(const vres_store *s, const vres_vtk_opts *o, const char *file, const char *name, size_t *npoints)
{
    if (o->domain >= 0 && (size_t)o->domain >= s->ndomains) {
        vres_error("%s: no domain %d: the store has %zu (0 to %zu)", name, o->domain, s->ndomains,
                   s->ndomains ? s->ndomains - 1 : 0);
        return -1;
    }
    // Which particles, and whether any of them has a normal worth writing.
    std::vector<std::vector<unsigned char>> show(s->ndomains);
    vtkIdType n = 0;
    bool have_normal = false;
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        show[k] = selection(s, o, k);
        for (size_t i = 0; i < show[k].size(); i++) {
            if (!show[k][i]) continue;
            n++;
            if (d->normal && (d->normal[3 * i] != 0 || d->normal[3 * i + 1] != 0 || d->normal[3 * i + 2] != 0))
                have_normal = true;
        }
    }
    unsigned f = o->fields;
    if (o->normal_auto && !have_normal) f &= ~(unsigned)VRES_VTK_NORMAL;

    vtk_quiet quiet; // from here on VTK's complaints (a failed allocation too) are captured
    vtkNew<vtkUnstructuredGrid> grid;
    vtkNew<vtkDoubleArray> coords; // double: long domains keep millimetres far from the origin
    size_array(coords, 3, n);
    vtkNew<vtkPoints> pts;
    pts->SetData(coords);
    grid->SetPoints(pts);

    vtkPointData *pd = grid->GetPointData();
    int *a_dom = f & VRES_VTK_DOMAIN ? new_array<vtkIntArray>(pd, "Domain", 1, n)->GetPointer(0) : nullptr;
    unsigned char *a_type =
        f & VRES_VTK_TYPE ? new_array<vtkUnsignedCharArray>(pd, "Type", 1, n)->GetPointer(0) : nullptr;
    int *a_mk = f & VRES_VTK_MK ? new_array<vtkIntArray>(pd, "Mk", 1, n)->GetPointer(0) : nullptr;
    vtkTypeUInt64 *a_id = f & VRES_VTK_ID ? new_array<vtkTypeUInt64Array>(pd, "Id", 1, n)->GetPointer(0) : nullptr;
    float *a_vel = f & VRES_VTK_VELOCITY ? new_array<vtkFloatArray>(pd, "Velocity", 3, n)->GetPointer(0) : nullptr;
    float *a_rho = f & VRES_VTK_DENSITY ? new_array<vtkFloatArray>(pd, "Density", 1, n)->GetPointer(0) : nullptr;
    float *a_p = f & VRES_VTK_PRESSURE ? new_array<vtkFloatArray>(pd, "Pressure", 1, n)->GetPointer(0) : nullptr;
    double *a_m = f & VRES_VTK_MASS ? new_array<vtkDoubleArray>(pd, "Mass", 1, n)->GetPointer(0) : nullptr;
    double *a_dp = f & VRES_VTK_DP ? new_array<vtkDoubleArray>(pd, "Dp", 1, n)->GetPointer(0) : nullptr;
    float *a_nrm = f & VRES_VTK_NORMAL ? new_array<vtkFloatArray>(pd, "Normal", 3, n)->GetPointer(0) : nullptr;

    // One pass over the particles fills every array; a missing store array reads as zeros.
    double *xyz = coords->GetPointer(0);
    vtkIdType j = 0;
    for (size_t k = 0; k < s->ndomains; k++) {
        const vres_domain *d = &s->dom[k];
        for (size_t i = 0; i < show[k].size(); i++) {
            if (!show[k][i]) continue;
            int type = d->type ? (int)d->type[i] : (int)VRES_FLUID;
            for (int c = 0; c < 3; c++) {
                xyz[3 * j + c] = d->pos ? d->pos[3 * i + c] : 0;
                if (a_vel) a_vel[3 * j + c] = d->vel ? d->vel[3 * i + c] : 0;
                if (a_nrm) a_nrm[3 * j + c] = d->normal ? d->normal[3 * i + c] : 0;
            }
            if (a_dom) a_dom[j] = (int)k;
            if (a_type) a_type[j] = (unsigned char)type;
            if (a_mk) a_mk[j] = d->mk ? d->mk[i] : 0;
            if (a_id) a_id[j] = d->id ? d->id[i] : 0;
            if (a_rho) a_rho[j] = d->rho ? d->rho[i] : 0;
            if (a_p) a_p[j] = d->press ? d->press[i] : 0;
            if (a_m) a_m[j] = d->mass_p ? d->mass_p[i] : 0;
            if (a_dp) a_dp[j] = d->dp;
            j++;
        }
    }

    // Every point is a vertex cell: offsets 0..n, connectivity 0..n-1.
    vtkNew<vtkIdTypeArray> offsets, conn;
    size_array(offsets, 1, n + 1);
    size_array(conn, 1, n);
    for (vtkIdType i = 0; i < n; i++) offsets->SetValue(i, i), conn->SetValue(i, i);
    offsets->SetValue(n, n);
    vtkNew<vtkCellArray> cells;
    cells->SetData(offsets, conn);
    grid->SetCells(VTK_VERTEX, cells);

    // Field data: the Type legend and the time.
    vtkNew<vtkStringArray> legend;
    legend->SetName("TypeNames");
    legend->SetNumberOfValues(VRES_NTYPES);
    for (int t = 0; t < VRES_NTYPES; t++) legend->SetValue(t, vres_ptype_name(t));
    grid->GetFieldData()->AddArray(legend);
    vtkNew<vtkDoubleArray> tv;
    tv->SetName("TimeValue");
    tv->SetNumberOfTuples(1);
    tv->SetValue(0, s->time);
    grid->GetFieldData()->AddArray(tv);

    vtkNew<vtkXMLUnstructuredGridWriter> w;
    w->SetInputData(grid);
    w->SetFileName(file);
    w->SetDataModeToAppended();
    w->EncodeAppendedDataOff(); // raw binary: base64 would add a third for nothing
    w->SetCompressorTypeToZLib(); // readable by every VTK reader (LZ4 files are bigger, not all read them)
    w->SetCompressionLevel(1);    // zlib's fastest: much quicker than its default, barely larger
    w->SetHeaderTypeToUInt64(); // blocks above 4 GiB stay addressable
    w->Write();
    unsigned long code = w->GetErrorCode();
    if (code != 0 || quiet.cap->nerrors) {
        // The error code names the cause (errno or disk full) better than VTK's first message.
        const char *why = code ? error_code_text(code) : quiet.cap->first.c_str();
        vres_error("%s: cannot write VTK file: %s", name, *why ? why : "unknown VTK error");
        return -1;
    }
    if (npoints) *npoints = (size_t)n;
    return 0;
}

// Write s into a vres_outfile-managed temporary and rename it; exceptions left to the caller.
int write_atomic(const vres_store *s, const vres_vtk_opts *o, const char *path, size_t *npoints)
{
    vres_outfile out;
    if (vres_out_begin(&out, path) != 0) return -1;
    try {
        if (write_vtu(s, o, out.tmp, path, npoints) != 0) {
            vres_out_abort(&out);
            return -1;
        }
    } catch (...) {
        vres_out_abort(&out);
        throw;
    }
    return vres_out_commit(&out);
}

// Characters that must be escaped inside a double-quoted XML attribute.
void put_xml_attr(FILE *fp, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&': fputs("&amp;", fp); break;
        case '<': fputs("&lt;", fp); break;
        case '>': fputs("&gt;", fp); break;
        case '"': fputs("&quot;", fp); break;
        default: fputc(*s, fp);
        }
    }
}

} // namespace

struct vres_vtu {
    vtkSmartPointer<vtkUnstructuredGrid> grid; // what VTK's reader produced
};

extern "C" {

vres_vtk_opts vres_vtk_defaults(void)
{
    vres_vtk_opts o;
    o.fields = VRES_VTK_ALL;
    o.normal_auto = 1;
    o.buffers = 0;
    o.domain = -1;
    return o;
}

size_t vres_vtk_count(const vres_store *s, const vres_vtk_opts *o, size_t k, int t)
{
    try {
        if (k >= s->ndomains) return 0;
        std::vector<unsigned char> show = selection(s, o, k);
        const vres_domain *d = &s->dom[k];
        size_t n = 0;
        for (size_t i = 0; i < show.size(); i++)
            n += show[i] && (t < 0 || (d->type ? (int)d->type[i] : (int)VRES_FLUID) == t);
        return n;
    } catch (...) {
        vres_error("out of memory counting the particles to write");
        exit(1); // as vres_xmalloc does: a count has no error value
    }
}

const char *vres_vtk_field_name(unsigned f)
{
    for (int i = 0; i < nfields; i++)
        if (field_bits[i] == f) return field_names[i];
    return nullptr;
}

int vres_vtk_parse_fields(const char *list, vres_vtk_opts *o)
{
    unsigned mask = 0;
    const char *p = list;
    for (;;) {
        const char *end = strchr(p, ',');
        size_t len = end ? (size_t)(end - p) : strlen(p);
        int found = -1;
        for (int i = 0; i < nfields && found < 0; i++)
            if (strlen(field_names[i]) == len && strncasecmp(field_names[i], p, len) == 0) found = i;
        if (len == 0) {
            vres_error("empty field name in --fields '%s'", list);
            return -1;
        }
        if (found < 0) {
            char valid[256] = ""; // plain C here: nothing that can throw
            for (int i = 0; i < nfields; i++) {
                if (i) strcat(valid, ", ");
                strcat(valid, field_names[i]);
            }
            vres_error("unknown field '%.*s' in --fields (valid: %s)", (int)len, p, valid);
            return -1;
        }
        mask |= field_bits[found];
        if (!end) break;
        p = end + 1;
    }
    o->fields = mask;
    o->normal_auto = 0;
    return 0;
}

int vres_vtk_write_file(const vres_store *s, const vres_vtk_opts *o, const char *file, const char *name,
                        size_t *npoints)
{
    try {
        return write_vtu(s, o, file, name, npoints);
    } catch (const std::bad_alloc &) {
        report_exception(name, "out of memory building the VTK grid");
    } catch (const std::exception &e) {
        report_exception(name, e.what());
    } catch (...) {
        report_exception(name, "unexpected C++ exception in VTK");
    }
    return -1;
}

int vres_vtk_write(const vres_store *s, const vres_vtk_opts *o, const char *path, size_t *npoints)
{
    try {
        return write_atomic(s, o, path, npoints);
    } catch (const std::bad_alloc &) {
        report_exception(path, "out of memory building the VTK grid");
    } catch (const std::exception &e) {
        report_exception(path, e.what());
    } catch (...) {
        report_exception(path, "unexpected C++ exception in VTK");
    }
    return -1;
}

int vres_pvd_write_file(const char *file, const char *name, size_t n, const char *const *files,
                        const double *times)
{
    FILE *fp = fopen(file, "w");
    if (!fp) {
        vres_error("%s: cannot write: %s", name, strerror(errno));
        return -1;
    }
    fputs("<?xml version=\"1.0\"?>\n"
          "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
          "  <Collection>\n",
          fp);
    for (size_t i = 0; i < n; i++) {
        // %.17g: the time reads back as the same double.
        fprintf(fp, "    <DataSet timestep=\"%.17g\" group=\"\" part=\"0\" file=\"", times[i]);
        put_xml_attr(fp, files[i]);
        fputs("\"/>\n", fp);
    }
    fputs("  </Collection>\n</VTKFile>\n", fp);
    int bad = ferror(fp);
    if (fclose(fp) != 0) bad = 1;
    if (bad) {
        vres_error("%s: cannot write: %s", name, strerror(errno ? errno : EIO));
        return -1;
    }
    return 0;
}

vres_vtu *vres_vtu_read(const char *path)
{
    try {
        FILE *fp = fopen(path, "rb");
        if (!fp) {
            vres_error("%s: cannot open: %s", path, strerror(errno));
            return nullptr;
        }
        fclose(fp);
        vtk_quiet quiet;
        vtkNew<vtkXMLUnstructuredGridReader> r;
        r->SetFileName(path);
        r->Update();
        if (r->GetErrorCode() != 0 || quiet.cap->nerrors) {
            const char *why = quiet.cap->nerrors ? quiet.cap->first.c_str()
                                                 : error_code_text(r->GetErrorCode());
            vres_error("%s: not a readable VTK unstructured grid: %s", path, why);
            return nullptr;
        }
        vres_vtu *v = new vres_vtu;
        v->grid = r->GetOutput();
        return v;
    } catch (const std::exception &e) {
        report_exception(path, e.what());
    } catch (...) {
        report_exception(path, "unexpected C++ exception in VTK");
    }
    return nullptr;
}

void vres_vtu_free(vres_vtu *v)
{
    delete v;
}

size_t vres_vtu_npoints(const vres_vtu *v)
{
    return (size_t)v->grid->GetNumberOfPoints();
}

size_t vres_vtu_nvertices(const vres_vtu *v)
{
    size_t nv = 0;
    for (vtkIdType c = 0; c < v->grid->GetNumberOfCells(); c++)
        if (v->grid->GetCellType(c) == VTK_VERTEX) nv++;
    return nv;
}

void vres_vtu_point(const vres_vtu *v, size_t i, double xyz[3])
{
    v->grid->GetPoint((vtkIdType)i, xyz);
}

int vres_vtu_ncomp(const vres_vtu *v, const char *name)
{
    vtkAbstractArray *a = v->grid->GetPointData()->GetAbstractArray(name);
    return a ? a->GetNumberOfComponents() : 0;
}

const char *vres_vtu_type(const vres_vtu *v, const char *name)
{
    vtkAbstractArray *a = v->grid->GetPointData()->GetAbstractArray(name);
    return a ? a->GetDataTypeAsString() : nullptr;
}

double vres_vtu_value(const vres_vtu *v, const char *name, size_t i, int comp)
{
    vtkDataArray *a = v->grid->GetPointData()->GetArray(name);
    if (!a || (vtkIdType)i >= a->GetNumberOfTuples() || comp < 0 || comp >= a->GetNumberOfComponents())
        return NAN;
    return a->GetComponent((vtkIdType)i, comp);
}

const char *vres_vtu_field_string(const vres_vtu *v, const char *name, size_t i)
{
    vtkStringArray *a = vtkStringArray::SafeDownCast(v->grid->GetFieldData()->GetAbstractArray(name));
    if (!a || (vtkIdType)i >= a->GetNumberOfValues()) return nullptr;
    return a->GetValue((vtkIdType)i).c_str();
}

double vres_vtu_field_value(const vres_vtu *v, const char *name, size_t i)
{
    vtkDataArray *a = v->grid->GetFieldData()->GetArray(name);
    if (!a || (vtkIdType)i >= a->GetNumberOfValues()) return NAN;
    return a->GetComponent((vtkIdType)i / a->GetNumberOfComponents(), (int)((vtkIdType)i % a->GetNumberOfComponents()));
}

} // extern "C"
