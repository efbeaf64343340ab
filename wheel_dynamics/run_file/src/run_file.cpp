// wheelsim::runfile — implementation over the HDF5 C API (1.10). See run_file.h and
// docs/hdf5-layout.md. HDF5 writes the working copy; commit() publishes it by copy and rename. All
// HDF5 identifiers live in RAII Handles; every public method silences HDF5's automatic error
// printing for its duration and turns a failure into a RunFileError that carries the library's
// error stack as text.
#include "wheelsim/run_file/run_file.h"

#include <hdf5.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <utility>

namespace wheelsim::runfile {

namespace {

/// Rows per chunk of every time-series dataset (step, time, value): 1024 rows of a quaternion
/// are 32 KiB, well inside HDF5's default 1 MiB chunk cache.
constexpr hsize_t kChunkRows = 1024;

/// H5MD version written to /h5md:version (see docs/hdf5-layout.md for what follows H5MD).
constexpr int kH5mdVersion[2] = {1, 0};

double now_s() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

/// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle &&o) noexcept : id_(std::exchange(o.id_, H5I_INVALID_HID)), closer_(o.closer_) {}
  Handle &operator=(Handle &&o) noexcept {
    if (this != &o) {
      reset();
      id_ = std::exchange(o.id_, H5I_INVALID_HID);
      closer_ = o.closer_;
    }
    return *this;
  }
  Handle(const Handle &) = delete;
  Handle &operator=(const Handle &) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Closes the identifier; returns false if HDF5 reported an error.
  bool reset() {
    bool ok = true;
    if (id_ >= 0 && closer_ != nullptr)
      ok = closer_(id_) >= 0;
    id_ = H5I_INVALID_HID;
    return ok;
  }

private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

/// Turns HDF5's automatic error printing off for a scope (restored afterwards).
class QuietHdf5Errors {
public:
  QuietHdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &func_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, func_, data_); }
  QuietHdf5Errors(const QuietHdf5Errors &) = delete;
  QuietHdf5Errors &operator=(const QuietHdf5Errors &) = delete;

private:
  H5E_auto2_t func_ = nullptr;
  void *data_ = nullptr;
};

/// The current HDF5 error stack as one line (outermost call first), then clears it.
std::string hdf5_error_text() {
  std::string text;
  auto walker = [](unsigned, const H5E_error2_t *e, void *client) -> herr_t {
    auto *out = static_cast<std::string *>(client);
    if (e->desc != nullptr && *e->desc != '\0') {
      if (!out->empty())
        *out += ": ";
      *out += e->desc;
    }
    return 0;
  };
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, walker, &text);
  H5Eclear2(H5E_DEFAULT);
  return text.empty() ? std::string("(no HDF5 error description)") : text;
}

/// Splits "a/b/c" into its components; rejects empty names, empty components, "." and "..".
std::vector<std::string> split_name(const std::string &kind, const std::string &name) {
  std::vector<std::string> parts;
  std::string part;
  auto bad = [&](const std::string &why) {
    return RunFileError(kind + " name '" + name + "' is invalid: " + why +
                        " (expected components separated by '/', e.g. \"wheel/position\")");
  };
  if (name.empty())
    throw bad("it is empty");
  for (std::size_t i = 0; i <= name.size(); ++i) {
    if (i == name.size() || name[i] == '/') {
      if (part.empty())
        throw bad("it has an empty component (leading, trailing or double '/')");
      if (part == "." || part == "..")
        throw bad("'.' and '..' are not allowed");
      parts.push_back(part);
      part.clear();
    } else {
      part += name[i];
    }
  }
  return parts;
}

} // namespace

// ------------------------------------------------------------------------------------------------
struct RunFile::Impl {
  std::string path;         // the published file readers open
  std::string working_path; // what HDF5 writes: path + ".writing"
  std::string staging_path; // the copy being published: path + ".publishing"
  Handle file, parameters, observables, terrain;
  Handle health; // /health, after begin_health()
  Handle health_step, health_time, health_code, health_severity, health_message;
  hsize_t health_rows = 0;
  Handle lcpl;        // link creation: intermediate groups, UTF-8 names
  Handle gcpl;        // group creation: no object time stamps (files that diff)
  Handle string_type; // variable-length UTF-8 string

  [[noreturn]] void fail(const std::string &what) const {
    throw RunFileError("run file '" + path + "': " + what + ": " + hdf5_error_text());
  }
  hid_t check(hid_t id, const std::string &what) const {
    if (id < 0)
      fail(what);
    return id;
  }
  void check_status(herr_t status, const std::string &what) const {
    if (status < 0)
      fail(what);
  }

  Handle dataset_creation(bool track_times = false) const {
    Handle dcpl(check(H5Pcreate(H5P_DATASET_CREATE), "creating a property list"), H5Pclose);
    check_status(H5Pset_obj_track_times(dcpl.get(), track_times ? 1 : 0), "setting time tracking");
    return dcpl;
  }

  /// True if `name` (relative, possibly nested) exists below `loc`.
  bool exists(hid_t loc, const std::vector<std::string> &parts) const {
    std::string prefix;
    for (const auto &p : parts) {
      prefix += (prefix.empty() ? "" : "/") + p;
      const htri_t e = H5Lexists(loc, prefix.c_str(), H5P_DEFAULT);
      if (e < 0)
        fail("checking whether '" + prefix + "' exists");
      if (e == 0)
        return false;
    }
    return true;
  }

  void write_string_attribute(hid_t obj, const char *name, const std::string &value) const {
    Handle space(check(H5Screate(H5S_SCALAR), "creating a dataspace"), H5Sclose);
    Handle attr(
        check(H5Acreate2(obj, name, string_type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              std::string("creating attribute '") + name + "'"),
        H5Aclose);
    const char *p = value.c_str();
    check_status(H5Awrite(attr.get(), string_type.get(), &p),
                 std::string("writing attribute '") + name + "'");
  }

  void write_int_array_attribute(hid_t obj, const char *name, const int *values, hsize_t n) const {
    Handle space(check(H5Screate_simple(1, &n, nullptr), "creating a dataspace"), H5Sclose);
    Handle attr(check(H5Acreate2(obj, name, H5T_STD_I32LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                      std::string("creating attribute '") + name + "'"),
                H5Aclose);
    check_status(H5Awrite(attr.get(), H5T_NATIVE_INT, values),
                 std::string("writing attribute '") + name + "'");
  }

  Handle create_group(hid_t loc, const std::string &name) const {
    return Handle(check(H5Gcreate2(loc, name.c_str(), lcpl.get(), gcpl.get(), H5P_DEFAULT),
                        "creating group '" + name + "'"),
                  H5Gclose);
  }

  /// A scalar dataset `name` below `loc` of file type `file_type`, written from `mem_type`.
  void write_scalar_dataset(hid_t loc, const std::string &name, hid_t file_type, hid_t mem_type,
                            const void *value, const std::string &unit) const {
    Handle space(check(H5Screate(H5S_SCALAR), "creating a dataspace"), H5Sclose);
    Handle dcpl = dataset_creation();
    Handle ds(check(H5Dcreate2(loc, name.c_str(), file_type, space.get(), lcpl.get(), dcpl.get(),
                               H5P_DEFAULT),
                    "creating dataset '" + name + "'"),
              H5Dclose);
    check_status(H5Dwrite(ds.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, value),
                 "writing dataset '" + name + "'");
    if (!unit.empty())
      write_string_attribute(ds.get(), "unit", unit);
  }

  enum class ParamKind { Text, Float, Integer };
  void write_parameter(const std::string &name, ParamKind kind, const void *value,
                       const std::string &unit) const {
    const auto parts = split_name("parameter", name);
    if (exists(parameters.get(), parts))
      throw RunFileError("run file '" + path + "': parameter '" + name +
                         "' is already set (each parameter is written once)");
    if (kind != ParamKind::Text && unit.empty())
      throw RunFileError("run file '" + path + "': parameter '" + name +
                         "' needs a unit (use \"1\" for a dimensionless number)");
    switch (kind) {
    case ParamKind::Text: {
      const char *p = static_cast<const std::string *>(value)->c_str();
      write_scalar_dataset(parameters.get(), name, string_type.get(), string_type.get(), &p, "");
      break;
    }
    case ParamKind::Float:
      write_scalar_dataset(parameters.get(), name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, value, unit);
      break;
    case ParamKind::Integer:
      write_scalar_dataset(parameters.get(), name, H5T_STD_I64LE, H5T_NATIVE_INT64, value, unit);
      break;
    }
  }

  /// An empty 1-D extendable dataset `name` below `loc` (chunks of `chunk_rows`).
  Handle create_extendable(hid_t loc, const char *name, hid_t file_type, hsize_t chunk_rows) const {
    const hsize_t dims = 0, maxdims = H5S_UNLIMITED;
    Handle space(check(H5Screate_simple(1, &dims, &maxdims), "creating a dataspace"), H5Sclose);
    Handle dcpl = dataset_creation();
    check_status(H5Pset_chunk(dcpl.get(), 1, &chunk_rows), "setting the chunk size");
    return Handle(
        check(H5Dcreate2(loc, name, file_type, space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT),
              std::string("creating dataset '") + name + "'"),
        H5Dclose);
  }

  /// Writes row `row` of the 1-D dataset `ds` (extending it to row + 1 rows).
  void write_row(const Handle &ds, hsize_t row, hid_t mem_type, const void *value,
                 const std::string &what) const {
    const hsize_t rows = row + 1, count = 1;
    check_status(H5Dset_extent(ds.get(), &rows), what + ": extending");
    Handle fspace(check(H5Dget_space(ds.get()), what + ": dataspace"), H5Sclose);
    check_status(H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, &row, nullptr, &count, nullptr),
                 what + ": selecting the row");
    Handle mspace(check(H5Screate_simple(1, &count, nullptr), what + ": memory space"), H5Sclose);
    check_status(H5Dwrite(ds.get(), mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, value),
                 what + ": writing");
  }

  void flush_file() const {
    check_status(H5Fflush(file.get(), H5F_SCOPE_GLOBAL), "flushing (H5Fflush)");
  }

  /// Publishes the flushed working copy as `path`: copy to the staging name, then rename(2) onto
  /// `path`, which replaces it atomically — a reader (or a crash) sees the old or the new file,
  /// never a mix. Nothing is synced to the device: the guarantee is for process death.
  void publish() const {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::copy_file(working_path, staging_path, fs::copy_options::overwrite_existing, ec);
    if (ec)
      throw RunFileError("run file '" + path + "': copying the working copy '" + working_path +
                         "' to '" + staging_path + "': " + ec.message());
    fs::rename(staging_path, path, ec);
    if (ec)
      throw RunFileError("run file '" + path + "': renaming '" + staging_path +
                         "' onto it: " + ec.message());
  }
};

// ------------------------------------------------------------------------------------------------
struct TimeSeries::Datasets {
  Handle group, step, time, value;
};

TimeSeries::TimeSeries(RunFile &owner, std::string name, std::string unit, int components,
                       std::unique_ptr<Datasets> datasets)
    : owner_(&owner), name_(std::move(name)), unit_(std::move(unit)), components_(components),
      datasets_(std::move(datasets)) {}

TimeSeries::~TimeSeries() = default;

void TimeSeries::append(std::int64_t step, double time_s, const double *values) {
  owner_->require_open("append to an observable");
  if (values == nullptr)
    throw RunFileError("observable '" + name_ + "': append with a null values pointer");
  if (step < 0)
    throw RunFileError("observable '" + name_ + "': step " + std::to_string(step) +
                       " is negative (steps are >= 0; -1 marks rows a crash left unwritten)");
  if (has_last_step_ && step <= last_step_)
    throw RunFileError("observable '" + name_ + "': step " + std::to_string(step) +
                       " appended after step " + std::to_string(last_step_) +
                       " (steps must increase)");
  // A flush that has become due is done before this row is buffered: when the rig appends every
  // observable of step n before any of step n+1, each flush then ends at a step boundary.
  owner_->before_append(*this);
  steps_.push_back(step);
  times_.push_back(time_s);
  values_.insert(values_.end(), values, values + components_);
  last_step_ = step;
  has_last_step_ = true;
}

void TimeSeries::append(std::int64_t step, double time_s, double value) {
  if (components_ != 1)
    throw RunFileError("observable '" + name_ + "' has " + std::to_string(components_) +
                       " components: append a pointer to that many values, not one scalar");
  append(step, time_s, &value);
}

void TimeSeries::write_buffered() {
  const hsize_t n = steps_.size();
  if (n == 0)
    return;
  const RunFile::Impl &f = *owner_->impl_;
  const hsize_t old_rows = static_cast<hsize_t>(rows_written_);
  const hsize_t comps = static_cast<hsize_t>(components_);
  auto extend_and_write = [&](const Handle &ds, const char *what, int rank, hid_t mem_type,
                              const void *data) {
    const std::string where = "observable '" + name_ + "' " + what;
    const hsize_t new_dims[2] = {old_rows + n, comps};
    f.check_status(H5Dset_extent(ds.get(), new_dims), where + ": extending");
    Handle fspace(f.check(H5Dget_space(ds.get()), where + ": dataspace"), H5Sclose);
    const hsize_t start[2] = {old_rows, 0};
    const hsize_t count[2] = {n, comps};
    f.check_status(
        H5Sselect_hyperslab(fspace.get(), H5S_SELECT_SET, start, nullptr, count, nullptr),
        where + ": selecting rows");
    Handle mspace(f.check(H5Screate_simple(rank, count, nullptr), where + ": memory space"),
                  H5Sclose);
    f.check_status(H5Dwrite(ds.get(), mem_type, mspace.get(), fspace.get(), H5P_DEFAULT, data),
                   where + ": writing rows");
  };
  extend_and_write(datasets_->step, "step", 1, H5T_NATIVE_INT64, steps_.data());
  extend_and_write(datasets_->time, "time", 1, H5T_NATIVE_DOUBLE, times_.data());
  extend_and_write(datasets_->value, "value", components_ == 1 ? 1 : 2, H5T_NATIVE_DOUBLE,
                   values_.data());
  rows_written_ += static_cast<std::int64_t>(n);
  steps_.clear();
  times_.clear();
  values_.clear();
}

void TimeSeries::close_datasets() {
  datasets_->value.reset();
  datasets_->time.reset();
  datasets_->step.reset();
  datasets_->group.reset();
}

// ------------------------------------------------------------------------------------------------
RunFile::RunFile(const std::string &path, const Creator &creator, const FlushPolicy &policy)
    : path_(path), impl_(std::make_unique<Impl>()) {
  set_flush_policy(policy);
  QuietHdf5Errors quiet;
  Impl &f = *impl_;
  f.path = path;
  f.working_path = working_path();
  f.staging_path = path + ".publishing";

  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!dir.empty() && !std::filesystem::is_directory(dir, ec))
    throw RunFileError("cannot create run file '" + path + "': directory '" + dir.string() +
                       "' does not exist (create it first or choose another --out path)");

  // HDF5 file format 2 (library 1.8 objects), as H5MD recommends; not the 1.10 format, whose
  // superblock marks a crashed writer's file as "still open" (unreadable without h5clear).
  Handle fapl(f.check(H5Pcreate(H5P_FILE_ACCESS), "creating a property list"), H5Pclose);
  f.check_status(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V18),
                 "setting the file format version");
  if (std::filesystem::is_directory(path, ec))
    throw RunFileError("cannot create run file '" + path + "': it is a directory");
  std::filesystem::remove(f.staging_path, ec); // left by a writer that was killed
  const hid_t file = H5Fcreate(f.working_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl.get());
  if (file < 0)
    throw RunFileError("cannot create run file '" + path + "' (working copy '" + f.working_path +
                       "'): " + hdf5_error_text());
  f.file = Handle(file, H5Fclose);

  open_file_objects(true);
  {
    Handle h5md = f.create_group(file, "h5md");
    f.write_int_array_attribute(h5md.get(), "version", kH5mdVersion, 2);
    Handle creator_group = f.create_group(h5md.get(), "creator");
    f.write_string_attribute(creator_group.get(), "name", creator.name);
    f.write_string_attribute(creator_group.get(), "version", creator.version);
    f.write_string_attribute(creator_group.get(), "git_revision", creator.git_revision);
    std::string author = creator.author;
    if (author.empty()) {
      const char *user = std::getenv("USER");
      author = (user != nullptr && *user != '\0') ? user : "unknown";
    }
    Handle author_group = f.create_group(h5md.get(), "author");
    f.write_string_attribute(author_group.get(), "name", author);
  }
  f.parameters = f.create_group(file, "parameters");
  f.observables = f.create_group(file, "observables");
  f.terrain = f.create_group(file, "terrain");
  commit();
}

RunFile::RunFile(const std::string &path, const Resume &resume, const FlushPolicy &policy)
    : path_(path), impl_(std::make_unique<Impl>()) {
  set_flush_policy(policy);
  QuietHdf5Errors quiet;
  Impl &f = *impl_;
  f.path = path;
  f.working_path = working_path();
  f.staging_path = path + ".publishing";
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw RunFileError("cannot resume run file '" + path +
                       "': it does not exist (no committed file of the stopped run)");
  fs::remove(f.staging_path, ec); // left by a writer that was killed
  fs::copy_file(path, f.working_path, fs::copy_options::overwrite_existing, ec);
  if (ec)
    throw RunFileError("cannot resume run file '" + path + "': copying it to '" + f.working_path +
                       "': " + ec.message());
  Handle fapl(f.check(H5Pcreate(H5P_FILE_ACCESS), "creating a property list"), H5Pclose);
  f.check_status(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V18),
                 "setting the file format version");
  const hid_t file = H5Fopen(f.working_path.c_str(), H5F_ACC_RDWR, fapl.get());
  if (file < 0)
    throw RunFileError("cannot resume run file '" + path +
                       "': HDF5 cannot open it: " + hdf5_error_text());
  f.file = Handle(file, H5Fclose);
  open_file_objects(false);
  truncate_resumed(resume.before_step);
  commit();
}

void RunFile::open_file_objects(bool create) {
  Impl &f = *impl_;
  f.lcpl = Handle(f.check(H5Pcreate(H5P_LINK_CREATE), "creating a property list"), H5Pclose);
  f.check_status(H5Pset_create_intermediate_group(f.lcpl.get(), 1), "link property list");
  f.check_status(H5Pset_char_encoding(f.lcpl.get(), H5T_CSET_UTF8), "link property list");
  f.gcpl = Handle(f.check(H5Pcreate(H5P_GROUP_CREATE), "creating a property list"), H5Pclose);
  f.check_status(H5Pset_obj_track_times(f.gcpl.get(), 0), "group property list");
  f.string_type = Handle(f.check(H5Tcopy(H5T_C_S1), "creating the string type"), H5Tclose);
  f.check_status(H5Tset_size(f.string_type.get(), H5T_VARIABLE), "string type");
  f.check_status(H5Tset_cset(f.string_type.get(), H5T_CSET_UTF8), "string type");
  if (create)
    return;
  auto open_group = [&](const char *name) {
    if (H5Lexists(f.file.get(), name, H5P_DEFAULT) <= 0)
      throw RunFileError("cannot resume run file '" + path_ + "': no /" + name +
                         " (not a run file of wheel-rig)");
    return Handle(
        f.check(H5Gopen2(f.file.get(), name, H5P_DEFAULT), std::string("opening /") + name),
        H5Gclose);
  };
  f.parameters = open_group("parameters");
  f.observables = open_group("observables");
  f.terrain = open_group("terrain");
  if (H5Lexists(f.file.get(), "health", H5P_DEFAULT) > 0) {
    f.health = open_group("health");
    auto open = [&](const char *name) {
      return Handle(f.check(H5Dopen2(f.health.get(), name, H5P_DEFAULT),
                            std::string("opening /health/") + name),
                    H5Dclose);
    };
    f.health_step = open("step");
    f.health_time = open("time");
    f.health_code = open("code");
    f.health_severity = open("severity");
    f.health_message = open("message");
  }
}

void RunFile::truncate_resumed(std::int64_t before_step) {
  Impl &f = *impl_;
  // The steps of a 1-D int64 dataset.
  auto read_steps = [&f](hid_t ds, const std::string &what) {
    Handle space(f.check(H5Dget_space(ds), what + ": dataspace"), H5Sclose);
    hsize_t dims[2] = {0, 0};
    f.check(H5Sget_simple_extent_dims(space.get(), dims, nullptr), what + ": extent");
    std::vector<std::int64_t> steps(dims[0]);
    if (dims[0] > 0)
      f.check_status(H5Dread(ds, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, steps.data()),
                     what + ": reading");
    return steps;
  };
  // Rows before the first with step >= before_step or an unwritten one (step -1).
  auto rows_before = [before_step](const std::vector<std::int64_t> &steps) {
    std::int64_t k = 0;
    while (k < static_cast<std::int64_t>(steps.size()) && steps[k] >= 0 && steps[k] < before_step)
      ++k;
    return k;
  };
  // Cuts a dataset to `rows` rows (its other dimension kept).
  auto cut_rows = [&f](hid_t ds, std::int64_t rows, const std::string &what) {
    Handle space(f.check(H5Dget_space(ds), what + ": dataspace"), H5Sclose);
    hsize_t dims[2] = {0, 0};
    f.check(H5Sget_simple_extent_dims(space.get(), dims, nullptr), what + ": extent");
    dims[0] = static_cast<hsize_t>(rows);
    f.check_status(H5Dset_extent(ds, dims),
                   what + ": cutting to " + std::to_string(rows) + " rows");
  };
  std::vector<std::string> groups; // every series: a group holding a dataset 'step'
  auto visit = [](hid_t, const char *name, const H5L_info_t *, void *data) -> herr_t {
    const std::string n(name);
    if (n == "step" || (n.size() > 5 && n.compare(n.size() - 5, 5, "/step") == 0))
      static_cast<std::vector<std::string> *>(data)->push_back(n.substr(0, n.size() - 5));
    return 0;
  };
  f.check_status(H5Lvisit(f.observables.get(), H5_INDEX_NAME, H5_ITER_NATIVE, visit, &groups),
                 "listing /observables");
  for (const std::string &g : groups) {
    const std::string where = "observable '" + g + "'";
    Handle group(f.check(H5Gopen2(f.observables.get(), g.c_str(), H5P_DEFAULT), where), H5Gclose);
    Handle step(f.check(H5Dopen2(group.get(), "step", H5P_DEFAULT), where + " step"), H5Dclose);
    const std::vector<std::int64_t> steps = read_steps(step.get(), where + " step");
    const std::int64_t keep = rows_before(steps);
    for (const char *name : {"step", "time", "value"}) {
      Handle ds(f.check(H5Dopen2(group.get(), name, H5P_DEFAULT), where + " " + name), H5Dclose);
      cut_rows(ds.get(), keep, where + " " + name);
    }
    resumed_rows_[g] = {keep, keep > 0 ? steps[keep - 1] : -1};
  }
  if (f.health.valid()) {
    const std::int64_t keep = rows_before(read_steps(f.health_step.get(), "/health/step"));
    for (Handle *h :
         {&f.health_step, &f.health_time, &f.health_code, &f.health_severity, &f.health_message})
      cut_rows(h->get(), keep, "/health");
    f.health_rows = static_cast<hsize_t>(keep);
  }
}

bool RunFile::has_parameter(const std::string &name) const {
  require_open("look up a parameter");
  QuietHdf5Errors quiet;
  return impl_->exists(impl_->parameters.get(), split_name("parameter", name));
}

bool RunFile::has_health() const { return is_open() && impl_->health.valid(); }

RunFile::~RunFile() {
  try {
    close();
  } catch (const std::exception &e) {
    std::fprintf(stderr, "wheelsim::runfile: closing '%s' failed: %s\n", path_.c_str(), e.what());
  }
}

bool RunFile::is_open() const { return impl_ && impl_->file.valid(); }

void RunFile::require_open(const char *what) const {
  if (!is_open())
    throw RunFileError("run file '" + path_ + "': cannot " + what + ": the file is closed");
}

void RunFile::set_flush_policy(const FlushPolicy &policy) {
  if (policy.write_every_rows < 0 || !(policy.commit_interval_s >= 0.0) ||
      !(policy.commit_cost_factor >= 0.0))
    throw RunFileError("run file '" + path_ + "': write_every_rows must be >= 0 rows, " +
                       "commit_interval >= 0 s and commit_cost_factor >= 0 (0 disables each), " +
                       "got " + std::to_string(policy.write_every_rows) + " rows, " +
                       std::to_string(policy.commit_interval_s) + " s and " +
                       std::to_string(policy.commit_cost_factor));
  policy_ = policy;
}

// --- parameters ----------------------------------------------------------------------------------
void RunFile::set_parameter_text(const std::string &name, const std::string &text) {
  require_open("set a parameter");
  QuietHdf5Errors quiet;
  impl_->write_parameter(name, Impl::ParamKind::Text, &text, "");
  commit();
}

void RunFile::set_parameter(const std::string &name, const std::string &value) {
  set_parameter_text(name, value);
}

void RunFile::set_parameter(const std::string &name, const char *value) {
  if (value == nullptr)
    throw RunFileError("run file '" + path_ + "': parameter '" + name + "' is a null string");
  set_parameter_text(name, std::string(value));
}

void RunFile::set_parameter(const std::string &name, double value, const std::string &unit) {
  require_open("set a parameter");
  QuietHdf5Errors quiet;
  impl_->write_parameter(name, Impl::ParamKind::Float, &value, unit);
  commit();
}

void RunFile::set_parameter(const std::string &name, std::int64_t value, const std::string &unit) {
  require_open("set a parameter");
  QuietHdf5Errors quiet;
  impl_->write_parameter(name, Impl::ParamKind::Integer, &value, unit);
  commit();
}

void RunFile::set_parameter(const std::string &name, int value, const std::string &unit) {
  set_parameter(name, static_cast<std::int64_t>(value), unit);
}

// --- observables ---------------------------------------------------------------------------------
TimeSeries &RunFile::observable(const std::string &name, const std::string &unit, int components) {
  require_open("declare an observable");
  auto found = series_.find(name);
  if (found != series_.end()) {
    const TimeSeries &s = *found->second;
    if (s.unit() != unit || s.components() != components)
      throw RunFileError("run file '" + path_ + "': observable '" + name + "' exists with unit '" +
                         s.unit() + "' and " + std::to_string(s.components()) +
                         " components; asked again with unit '" + unit + "' and " +
                         std::to_string(components));
    return *found->second;
  }
  const auto parts = split_name("observable", name);
  if (unit.empty())
    throw RunFileError("run file '" + path_ + "': observable '" + name +
                       "' needs a unit (use \"1\" for a dimensionless quantity)");
  if (components < 1)
    throw RunFileError("run file '" + path_ + "': observable '" + name +
                       "' needs components >= 1 (1 scalar, 3 vector, 4 quaternion), got " +
                       std::to_string(components));

  QuietHdf5Errors quiet;
  Impl &f = *impl_;
  if (const auto resumed = resumed_rows_.find(name); resumed != resumed_rows_.end()) {
    auto ds = std::make_unique<TimeSeries::Datasets>();
    const std::string where = "run file '" + path_ + "': resumed observable '" + name + "'";
    ds->group =
        Handle(f.check(H5Gopen2(f.observables.get(), name.c_str(), H5P_DEFAULT), where), H5Gclose);
    ds->step = Handle(f.check(H5Dopen2(ds->group.get(), "step", H5P_DEFAULT), where), H5Dclose);
    ds->time = Handle(f.check(H5Dopen2(ds->group.get(), "time", H5P_DEFAULT), where), H5Dclose);
    ds->value = Handle(f.check(H5Dopen2(ds->group.get(), "value", H5P_DEFAULT), where), H5Dclose);
    Handle space(f.check(H5Dget_space(ds->value.get()), where), H5Sclose);
    hsize_t dims[2] = {0, 1};
    const int rank = f.check(H5Sget_simple_extent_dims(space.get(), dims, nullptr), where);
    const int stored = rank == 1 ? 1 : static_cast<int>(dims[1]);
    Handle attr(f.check(H5Aopen(ds->value.get(), "unit", H5P_DEFAULT), where + ": unit"), H5Aclose);
    char *text = nullptr;
    f.check_status(H5Aread(attr.get(), f.string_type.get(), &text), where + ": unit");
    const std::string stored_unit = text != nullptr ? text : "";
    H5free_memory(text);
    if (stored != components || stored_unit != unit)
      throw RunFileError(where + " has unit '" + stored_unit + "' and " + std::to_string(stored) +
                         " components; the resumed run asks for '" + unit + "' and " +
                         std::to_string(components));
    std::unique_ptr<TimeSeries> series(
        new TimeSeries(*this, name, unit, components, std::move(ds)));
    series->rows_written_ = resumed->second.first;
    series->has_last_step_ = resumed->second.first > 0;
    series->last_step_ = resumed->second.second;
    resumed_rows_.erase(resumed);
    TimeSeries &ref = *series;
    series_.emplace(name, std::move(series));
    return ref;
  }
  if (f.exists(f.observables.get(), parts))
    throw RunFileError("run file '" + path_ + "': observable '" + name +
                       "' collides with an existing group (e.g. 'wheel' vs 'wheel/position')");
  auto ds = std::make_unique<TimeSeries::Datasets>();
  ds->group = f.create_group(f.observables.get(), name);

  // Fill values mark rows whose extent reached the disk but whose data did not (a kill inside a
  // flush): step -1, time and value NaN. See docs/hdf5-layout.md, "Crash guarantees".
  const std::int64_t step_fill = kUnwrittenStep;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto make = [&](const char *what, int rank, hid_t file_type, hid_t fill_type, const void *fill) {
    const hsize_t dims[2] = {0, static_cast<hsize_t>(components)};
    const hsize_t maxdims[2] = {H5S_UNLIMITED, static_cast<hsize_t>(components)};
    const hsize_t chunk[2] = {kChunkRows, static_cast<hsize_t>(components)};
    Handle space(f.check(H5Screate_simple(rank, dims, maxdims), "creating a dataspace"), H5Sclose);
    Handle dcpl = f.dataset_creation();
    f.check_status(H5Pset_chunk(dcpl.get(), rank, chunk), "setting the chunk size");
    f.check_status(H5Pset_fill_value(dcpl.get(), fill_type, fill), "setting the fill value");
    return Handle(f.check(H5Dcreate2(ds->group.get(), what, file_type, space.get(), H5P_DEFAULT,
                                     dcpl.get(), H5P_DEFAULT),
                          "creating dataset '" + name + "/" + what + "'"),
                  H5Dclose);
  };
  ds->step = make("step", 1, H5T_STD_I64LE, H5T_NATIVE_INT64, &step_fill);
  ds->time = make("time", 1, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &nan);
  f.write_string_attribute(ds->time.get(), "unit", "s");
  ds->value = make("value", components == 1 ? 1 : 2, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &nan);
  f.write_string_attribute(ds->value.get(), "unit", unit);
  commit();

  std::unique_ptr<TimeSeries> series(new TimeSeries(*this, name, unit, components, std::move(ds)));
  TimeSeries &ref = *series;
  series_.emplace(name, std::move(series));
  return ref;
}

void RunFile::before_append(const TimeSeries &series) {
  if (policy_.commit_interval_s > 0.0 &&
      now_s() - last_commit_s_ >= std::max(policy_.commit_interval_s,
                                           policy_.commit_cost_factor * last_commit_duration_s_)) {
    flush();
    return;
  }
  if (policy_.write_every_rows > 0 && series.buffered_rows() >= policy_.write_every_rows) {
    QuietHdf5Errors quiet;
    write_buffered_rows();
  }
}

// --- terrain -------------------------------------------------------------------------------------
void RunFile::write_snapshot(const std::string &group_name, std::int64_t step, double time_s,
                             const Grid2D &grid, const std::string &unit,
                             const std::vector<SnapshotScalar> &scalars) {
  require_open("write a terrain snapshot");
  const auto parts = split_name("terrain snapshot", group_name);
  const std::string where = "run file '" + path_ + "': terrain snapshot '" + group_name + "'";
  if (grid.values == nullptr || grid.rows == 0 || grid.cols == 0)
    throw RunFileError(where + ": the grid must have rows > 0, cols > 0 and values, got " +
                       std::to_string(grid.rows) + " x " + std::to_string(grid.cols));
  if (unit.empty())
    throw RunFileError(where + ": needs a unit (use \"1\" for dimensionless)");
  for (const auto &s : scalars) {
    split_name("terrain snapshot scalar", s.name);
    if (s.name == "step" || s.name == "time" || s.name == "value")
      throw RunFileError(where + ": scalar name '" + s.name + "' is reserved");
    if (s.unit.empty())
      throw RunFileError(where + ": scalar '" + s.name + "' needs a unit (\"1\" if none)");
  }
  QuietHdf5Errors quiet;
  Impl &f = *impl_;
  if (f.exists(f.terrain.get(), parts))
    throw RunFileError(where + " already exists (each snapshot name is written once)");
  Handle group = f.create_group(f.terrain.get(), group_name);
  f.write_scalar_dataset(group.get(), "step", H5T_STD_I64LE, H5T_NATIVE_INT64, &step, "");
  f.write_scalar_dataset(group.get(), "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &time_s, "s");
  {
    const hsize_t dims[2] = {grid.rows, grid.cols};
    Handle space(f.check(H5Screate_simple(2, dims, nullptr), "creating a dataspace"), H5Sclose);
    Handle dcpl = f.dataset_creation();
    Handle ds(f.check(H5Dcreate2(group.get(), "value", H5T_IEEE_F64LE, space.get(), H5P_DEFAULT,
                                 dcpl.get(), H5P_DEFAULT),
                      where + ": creating 'value'"),
              H5Dclose);
    f.check_status(
        H5Dwrite(ds.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, grid.values),
        where + ": writing 'value'");
    f.write_string_attribute(ds.get(), "unit", unit);
  }
  for (const auto &s : scalars)
    f.write_scalar_dataset(group.get(), s.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &s.value,
                           s.unit);
  commit();
}

// --- health --------------------------------------------------------------------------------------
void RunFile::begin_health(const std::string &status) {
  require_open("begin /health");
  Impl &f = *impl_;
  if (f.health.valid())
    throw RunFileError("run file '" + path_ + "': /health exists already (begin_health once)");
  QuietHdf5Errors quiet;
  f.health = f.create_group(f.file.get(), "health");
  f.write_string_attribute(f.health.get(), "status", status);
  const hsize_t chunk = 16;
  f.health_step = f.create_extendable(f.health.get(), "step", H5T_STD_I64LE, chunk);
  f.health_time = f.create_extendable(f.health.get(), "time", H5T_IEEE_F64LE, chunk);
  f.write_string_attribute(f.health_time.get(), "unit", "s");
  f.health_code = f.create_extendable(f.health.get(), "code", f.string_type.get(), chunk);
  f.health_severity = f.create_extendable(f.health.get(), "severity", f.string_type.get(), chunk);
  f.health_message = f.create_extendable(f.health.get(), "message", f.string_type.get(), chunk);
  commit();
}

void RunFile::add_health_finding(const HealthRecord &r) {
  require_open("add a health finding");
  Impl &f = *impl_;
  if (!f.health.valid())
    throw RunFileError("run file '" + path_ + "': add_health_finding before begin_health");
  QuietHdf5Errors quiet;
  const hsize_t row = f.health_rows;
  const char *code = r.code.c_str(), *severity = r.severity.c_str(), *message = r.message.c_str();
  f.write_row(f.health_step, row, H5T_NATIVE_INT64, &r.step, "/health/step");
  f.write_row(f.health_time, row, H5T_NATIVE_DOUBLE, &r.time_s, "/health/time");
  f.write_row(f.health_code, row, f.string_type.get(), &code, "/health/code");
  f.write_row(f.health_severity, row, f.string_type.get(), &severity, "/health/severity");
  f.write_row(f.health_message, row, f.string_type.get(), &message, "/health/message");
  ++f.health_rows;
  commit();
}

void RunFile::set_health_status(const std::string &status) {
  require_open("set the health status");
  Impl &f = *impl_;
  if (!f.health.valid())
    throw RunFileError("run file '" + path_ + "': set_health_status before begin_health");
  QuietHdf5Errors quiet;
  f.check_status(H5Adelete(f.health.get(), "status"), "replacing /health status");
  f.write_string_attribute(f.health.get(), "status", status);
  commit();
}

// --- flush / close -------------------------------------------------------------------------------
void RunFile::write_buffered_rows() {
  for (auto &entry : series_)
    entry.second->write_buffered();
}

void RunFile::commit() {
  const double start_s = now_s();
  impl_->flush_file();
  impl_->publish();
  last_commit_s_ = now_s();
  last_commit_duration_s_ = last_commit_s_ - start_s;
}

void RunFile::flush() {
  require_open("flush");
  QuietHdf5Errors quiet;
  write_buffered_rows();
  commit();
  ++flush_count_;
}

void RunFile::close() {
  if (!is_open())
    return;
  std::string first_error;
  QuietHdf5Errors quiet;
  try {
    write_buffered_rows();
  } catch (const RunFileError &e) {
    first_error = e.what();
  }
  for (auto &entry : series_)
    entry.second->close_datasets();
  Impl &f = *impl_;
  for (Handle *h : {&f.health_step, &f.health_time, &f.health_code, &f.health_severity,
                    &f.health_message, &f.health})
    h->reset();
  f.terrain.reset();
  f.observables.reset();
  f.parameters.reset();
  f.string_type.reset();
  f.gcpl.reset();
  f.lcpl.reset();
  if (!f.file.reset() && first_error.empty())
    first_error = "run file '" + path_ + "': closing (H5Fclose): " + hdf5_error_text();
  if (!first_error.empty()) // `path` keeps the last commit; the working copy stays beside it
    throw RunFileError(first_error + " (the last commit is in '" + path_ + "')");
  // The closed working copy is complete: it replaces the last commit without a copy.
  std::error_code ec;
  std::filesystem::rename(f.working_path, path_, ec);
  if (ec)
    throw RunFileError("run file '" + path_ + "': renaming the closed working copy '" +
                       f.working_path + "' onto it: " + ec.message());
}

} // namespace wheelsim::runfile
