! libcbr — Fortran binding of the C ABI in include/cbr/cbr.h.
!
! This module is a thin iso_c_binding layer: every function of cbr.h is
! declared here with bind(C) under its C name, and every #define constant of
! cbr.h is an integer(c_int), parameter of the same name. Read cbr.h for what
! each function does; the conventions (status codes, last error message,
! caller-owned arrays) are the same.
!
! Using it
! --------
!   gfortran -I<prefix>/include/cbr/fortran my_code.f90 \
!            -L<prefix>/lib -lcbr_fortran -lcbr
! or, with pkg-config (fmoddir is the directory of cbr.mod):
!   gfortran -I$(pkg-config --variable=fmoddir cbr) my_code.f90 \
!            $(pkg-config --libs cbr-fortran)
! or, with CMake: find_package(cbr) and link the target cbr::fortran.
!
! The interfaces of the C functions need only -lcbr. The Fortran helper
! cbr_f_string is compiled code: it lives in the static library
! libcbr_fortran.a, installed beside libcbr.so (hence -lcbr_fortran).
!
! The installed cbr.mod is the one compiled by gfortran when libcbr was
! built. With another Fortran compiler, compile the installed source
! <prefix>/include/cbr/fortran/cbr.f90 yourself (it is standard Fortran 2008)
! together with your program, and link -lcbr.
!
! Mapping of the C types
! ----------------------
!   cbr_mesh *, const char *   type(c_ptr)
!   int                        integer(c_int)
!   int64_t                    integer(c_int64_t)   e.g. 9_c_int64_t
!   double                     real(c_double)
!   const double *xyz          real(c_double) :: xyz(*)   an xyz(3, n) array
!                                                         passes as is
!   int64_t *tets_out          integer(c_int64_t) :: tets(*)   tets(4, ntet)
!
! Strings returned by the library (cbr_version, cbr_status_string,
! cbr_mesh_last_error) are C pointers; cbr_f_string turns one into a
! Fortran character(:), allocatable:
!     print *, cbr_f_string(cbr_mesh_last_error(mesh))
!
! Fortran-style 1-based ids: right after creating a mesh, call
!     status = cbr_mesh_set_param(mesh, CBR_PARAM_INDEX_BASE, 1.0_c_double)
! and every point id passed in or returned (e.g. by cbr_mesh_get_tets) is
! 1-based: the first point inserted is 1.
!
! Example
! -------
!     use, intrinsic :: iso_c_binding
!     use cbr
!     type(c_ptr) :: mesh
!     real(c_double) :: xyz(3, 4)
!     integer(c_int64_t), allocatable :: tets(:, :)
!     integer(c_int) :: status
!     xyz = reshape([0d0,0d0,0d0, 1d0,0d0,0d0, 0d0,1d0,0d0, 0d0,0d0,1d0], [3, 4])
!     status = cbr_mesh_create(mesh)
!     status = cbr_mesh_set_param(mesh, CBR_PARAM_INDEX_BASE, 1.0_c_double)
!     status = cbr_mesh_insert_points(mesh, 4_c_int64_t, xyz)
!     if (status /= CBR_OK) print *, cbr_f_string(cbr_mesh_last_error(mesh))
!     allocate(tets(4, cbr_mesh_tet_count(mesh)))
!     status = cbr_mesh_get_tets(mesh, tets)
!     call cbr_mesh_destroy(mesh)
!
! Keep this file in step with cbr.h: tests/abi checks that every function
! and constant of the header is declared here with the same value.
module cbr
  use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_int32_t, c_int64_t, c_double, &
                                         c_char, c_size_t, c_associated, &
                                         c_f_pointer
  implicit none
  private

  ! ---------------------------------------------------------------------
  ! Constants (same names and values as the #defines of cbr.h)
  ! ---------------------------------------------------------------------

  ! Version of the header this module was written for.
  integer(c_int), parameter, public :: CBR_VERSION_MAJOR = 0
  integer(c_int), parameter, public :: CBR_VERSION_MINOR = 1
  integer(c_int), parameter, public :: CBR_VERSION_PATCH = 0

  ! Status codes.
  integer(c_int), parameter, public :: CBR_OK = 0
  integer(c_int), parameter, public :: CBR_ERR_INVALID_ARGUMENT = -1
  integer(c_int), parameter, public :: CBR_ERR_INVALID_INPUT = -2
  integer(c_int), parameter, public :: CBR_ERR_OUT_OF_MEMORY = -3
  integer(c_int), parameter, public :: CBR_ERR_RECOVERY_FAILED = -4
  integer(c_int), parameter, public :: CBR_ERR_IO = -5
  integer(c_int), parameter, public :: CBR_ERR_INTERNAL = -6

  ! Parameter keys for cbr_mesh_set_param / cbr_mesh_get_param.
  integer(c_int), parameter, public :: CBR_PARAM_INDEX_BASE = 1
  integer(c_int), parameter, public :: CBR_PARAM_KEEP_EXTERIOR = 2
  integer(c_int), parameter, public :: CBR_PARAM_REFINE_SIZE = 3
  integer(c_int), parameter, public :: CBR_PARAM_REFINE_GRADING = 4
  integer(c_int), parameter, public :: CBR_PARAM_REFINE_QUALITY_BOUND = 5
  integer(c_int), parameter, public :: CBR_PARAM_REFINE_PASSES = 6
  integer(c_int), parameter, public :: CBR_PARAM_REFINE_SIZE_FROM_SURFACE = 7
  integer(c_int), parameter, public :: CBR_PARAM_REFINE_GROWTH = 8
  integer(c_int), parameter, public :: CBR_PARAM_RECOVERY_DEEP_FLIPS = 9
  integer(c_int), parameter, public :: CBR_PARAM_RECOVERY_RETRIES = 10
  integer(c_int), parameter, public :: CBR_PARAM_THREADS = 11

  ! Defect kinds of cbr_mesh_check_faces (cbr_mesh_defect_count, ...).
  integer(c_int), parameter, public :: CBR_DEFECT_ID_OUT_OF_RANGE = 1
  integer(c_int), parameter, public :: CBR_DEFECT_REPEATED_ID = 2
  integer(c_int), parameter, public :: CBR_DEFECT_ZERO_AREA = 3
  integer(c_int), parameter, public :: CBR_DEFECT_DUPLICATE_TRIANGLE = 4
  integer(c_int), parameter, public :: CBR_DEFECT_INTERSECTION = 5
  integer(c_int), parameter, public :: CBR_DEFECT_OPEN_EDGE = 6
  integer(c_int), parameter, public :: CBR_DEFECT_NONMANIFOLD_EDGE = 7

  ! Statistic keys of cbr_mesh_get_stat (the paper's Table I).
  integer(c_int), parameter, public :: CBR_STAT_TOTAL_VERTICES = 1
  integer(c_int), parameter, public :: CBR_STAT_BOUNDARY_VERTICES = 2
  integer(c_int), parameter, public :: CBR_STAT_MISSING_FACES = 3
  integer(c_int), parameter, public :: CBR_STAT_FACES_RECOVERED_BY_FLIPS = 4
  integer(c_int), parameter, public :: CBR_STAT_CONFORMING_POINTS = 5
  integer(c_int), parameter, public :: CBR_STAT_STEINER_GENERATED = 6
  integer(c_int), parameter, public :: CBR_STAT_STEINER_REMAINING = 7
  integer(c_int), parameter, public :: CBR_STAT_DELAUNAY_SECONDS = 8
  integer(c_int), parameter, public :: CBR_STAT_RECOVERY_SECONDS = 9
  integer(c_int), parameter, public :: CBR_STAT_TOTAL_SECONDS = 10
  integer(c_int), parameter, public :: CBR_STAT_REGION_COUNT = 11
  integer(c_int), parameter, public :: CBR_STAT_STEINER_INSIDE = 12
  ! After cbr_mesh_refine: the paper's Table II and refinement counts.
  integer(c_int), parameter, public :: CBR_STAT_QUALITY_AVERAGE = 20
  integer(c_int), parameter, public :: CBR_STAT_QUALITY_MIN = 21
  integer(c_int), parameter, public :: CBR_STAT_PERCENT_ABOVE_0_4 = 22
  integer(c_int), parameter, public :: CBR_STAT_PERCENT_BELOW_0_1 = 23
  integer(c_int), parameter, public :: CBR_STAT_BAD_TOUCHING_STEINER = 24
  integer(c_int), parameter, public :: CBR_STAT_DIHEDRAL_MIN = 25
  integer(c_int), parameter, public :: CBR_STAT_DIHEDRAL_MAX = 26
  integer(c_int), parameter, public :: CBR_STAT_FIELD_POINTS = 27
  integer(c_int), parameter, public :: CBR_STAT_REFINE_FLIPS = 28
  integer(c_int), parameter, public :: CBR_STAT_REFINE_SECONDS = 29
  integer(c_int), parameter, public :: CBR_STAT_REFINE_TETS = 30
  integer(c_int), parameter, public :: CBR_STAT_REFINE_OVERSIZE_TETS = 31

  ! ---------------------------------------------------------------------
  ! The C functions
  ! ---------------------------------------------------------------------

  public :: cbr_version, cbr_status_string
  public :: cbr_mesh_create, cbr_mesh_destroy, cbr_mesh_last_error
  public :: cbr_mesh_set_param, cbr_mesh_get_param
  public :: cbr_mesh_insert_points, cbr_mesh_point_count, cbr_mesh_tet_count
  public :: cbr_mesh_get_points, cbr_mesh_get_tets
  public :: cbr_mesh_check_faces, cbr_mesh_defect_count
  public :: cbr_mesh_defect_listed, cbr_mesh_get_defect
  public :: cbr_mesh_recover_faces, cbr_mesh_steiner_count, cbr_mesh_steiner_points
  public :: cbr_mesh_get_tet_regions, cbr_mesh_get_stat
  public :: cbr_mesh_refine, cbr_mesh_get_region_stat

  ! Fortran helper.
  public :: cbr_f_string

  interface
    ! const char *cbr_version(void);
    function cbr_version() bind(C, name="cbr_version") result(str)
      import :: c_ptr
      type(c_ptr) :: str
    end function cbr_version

    ! const char *cbr_status_string(int status);
    function cbr_status_string(status) bind(C, name="cbr_status_string") &
        result(str)
      import :: c_ptr, c_int
      integer(c_int), value, intent(in) :: status
      type(c_ptr) :: str
    end function cbr_status_string

    ! int cbr_mesh_create(cbr_mesh **out);
    function cbr_mesh_create(out) bind(C, name="cbr_mesh_create") &
        result(status)
      import :: c_ptr, c_int
      type(c_ptr), intent(out) :: out
      integer(c_int) :: status
    end function cbr_mesh_create

    ! void cbr_mesh_destroy(cbr_mesh *mesh);
    subroutine cbr_mesh_destroy(mesh) bind(C, name="cbr_mesh_destroy")
      import :: c_ptr
      type(c_ptr), value, intent(in) :: mesh
    end subroutine cbr_mesh_destroy

    ! const char *cbr_mesh_last_error(const cbr_mesh *mesh);
    function cbr_mesh_last_error(mesh) bind(C, name="cbr_mesh_last_error") &
        result(str)
      import :: c_ptr
      type(c_ptr), value, intent(in) :: mesh
      type(c_ptr) :: str
    end function cbr_mesh_last_error

    ! int cbr_mesh_set_param(cbr_mesh *mesh, int key, double value);
    function cbr_mesh_set_param(mesh, key, value) &
        bind(C, name="cbr_mesh_set_param") result(status)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int), value, intent(in) :: key
      real(c_double), value, intent(in) :: value
      integer(c_int) :: status
    end function cbr_mesh_set_param

    ! int cbr_mesh_get_param(const cbr_mesh *mesh, int key, double *value);
    function cbr_mesh_get_param(mesh, key, value) &
        bind(C, name="cbr_mesh_get_param") result(status)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int), value, intent(in) :: key
      real(c_double), intent(out) :: value
      integer(c_int) :: status
    end function cbr_mesh_get_param

    ! int cbr_mesh_insert_points(cbr_mesh *mesh, int64_t count,
    !                            const double *xyz);
    function cbr_mesh_insert_points(mesh, count, xyz) &
        bind(C, name="cbr_mesh_insert_points") result(status)
      import :: c_ptr, c_int, c_int64_t, c_double
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int64_t), value, intent(in) :: count
      real(c_double), intent(in) :: xyz(*)
      integer(c_int) :: status
    end function cbr_mesh_insert_points

    ! int64_t cbr_mesh_point_count(const cbr_mesh *mesh);
    function cbr_mesh_point_count(mesh) bind(C, name="cbr_mesh_point_count") &
        result(count)
      import :: c_ptr, c_int64_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int64_t) :: count
    end function cbr_mesh_point_count

    ! int64_t cbr_mesh_tet_count(const cbr_mesh *mesh);
    function cbr_mesh_tet_count(mesh) bind(C, name="cbr_mesh_tet_count") &
        result(count)
      import :: c_ptr, c_int64_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int64_t) :: count
    end function cbr_mesh_tet_count

    ! int cbr_mesh_get_points(const cbr_mesh *mesh, double *xyz_out);
    function cbr_mesh_get_points(mesh, xyz_out) &
        bind(C, name="cbr_mesh_get_points") result(status)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value, intent(in) :: mesh
      real(c_double), intent(out) :: xyz_out(*)
      integer(c_int) :: status
    end function cbr_mesh_get_points

    ! int cbr_mesh_get_tets(const cbr_mesh *mesh, int64_t *tets_out);
    function cbr_mesh_get_tets(mesh, tets_out) &
        bind(C, name="cbr_mesh_get_tets") result(status)
      import :: c_ptr, c_int, c_int64_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int64_t), intent(out) :: tets_out(*)
      integer(c_int) :: status
    end function cbr_mesh_get_tets

    ! int cbr_mesh_recover_faces(cbr_mesh *mesh, int64_t count,
    !     const int64_t *tris, const int32_t *labels);
    ! labels may be NULL: pass c_null_ptr, or c_loc(labels) of a target array.
    function cbr_mesh_recover_faces(mesh, count, tris, labels) &
        bind(C, name="cbr_mesh_recover_faces") result(status)
      import :: c_ptr, c_int, c_int64_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int64_t), value, intent(in) :: count
      integer(c_int64_t), intent(in) :: tris(*)
      type(c_ptr), value, intent(in) :: labels
      integer(c_int) :: status
    end function cbr_mesh_recover_faces

    ! int64_t cbr_mesh_steiner_count(const cbr_mesh *mesh);
    function cbr_mesh_steiner_count(mesh) &
        bind(C, name="cbr_mesh_steiner_count") result(count)
      import :: c_ptr, c_int64_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int64_t) :: count
    end function cbr_mesh_steiner_count

    ! int cbr_mesh_steiner_points(const cbr_mesh *mesh, int64_t *ids_out);
    function cbr_mesh_steiner_points(mesh, ids_out) &
        bind(C, name="cbr_mesh_steiner_points") result(status)
      import :: c_ptr, c_int, c_int64_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int64_t), intent(out) :: ids_out(*)
      integer(c_int) :: status
    end function cbr_mesh_steiner_points

    ! int cbr_mesh_get_tet_regions(const cbr_mesh *mesh, int32_t *regions_out);
    function cbr_mesh_get_tet_regions(mesh, regions_out) &
        bind(C, name="cbr_mesh_get_tet_regions") result(status)
      import :: c_ptr, c_int, c_int32_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int32_t), intent(out) :: regions_out(*)
      integer(c_int) :: status
    end function cbr_mesh_get_tet_regions

    ! int cbr_mesh_get_stat(const cbr_mesh *mesh, int key, double *value);
    function cbr_mesh_get_stat(mesh, key, value) &
        bind(C, name="cbr_mesh_get_stat") result(status)
      import :: c_ptr, c_int, c_double
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int), value, intent(in) :: key
      real(c_double), intent(out) :: value
      integer(c_int) :: status
    end function cbr_mesh_get_stat

    ! int cbr_mesh_refine(cbr_mesh *mesh);
    function cbr_mesh_refine(mesh) &
        bind(C, name="cbr_mesh_refine") result(status)
      import :: c_ptr, c_int
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int) :: status
    end function cbr_mesh_refine

    ! int cbr_mesh_get_region_stat(const cbr_mesh *mesh, int32_t region,
    !                              int key, double *value);
    function cbr_mesh_get_region_stat(mesh, region, key, value) &
        bind(C, name="cbr_mesh_get_region_stat") result(status)
      import :: c_ptr, c_int, c_int32_t, c_double
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int32_t), value, intent(in) :: region
      integer(c_int), value, intent(in) :: key
      real(c_double), intent(out) :: value
      integer(c_int) :: status
    end function cbr_mesh_get_region_stat

    ! int cbr_mesh_check_faces(cbr_mesh *mesh, int64_t count,
    !                          const int64_t *tris);
    function cbr_mesh_check_faces(mesh, count, tris) &
        bind(C, name="cbr_mesh_check_faces") result(status)
      import :: c_ptr, c_int, c_int64_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int64_t), value, intent(in) :: count
      integer(c_int64_t), intent(in) :: tris(*)
      integer(c_int) :: status
    end function cbr_mesh_check_faces

    ! int64_t cbr_mesh_defect_count(const cbr_mesh *mesh, int kind);
    function cbr_mesh_defect_count(mesh, kind) &
        bind(C, name="cbr_mesh_defect_count") result(count)
      import :: c_ptr, c_int, c_int64_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int), value, intent(in) :: kind
      integer(c_int64_t) :: count
    end function cbr_mesh_defect_count

    ! int64_t cbr_mesh_defect_listed(const cbr_mesh *mesh, int kind);
    function cbr_mesh_defect_listed(mesh, kind) &
        bind(C, name="cbr_mesh_defect_listed") result(count)
      import :: c_ptr, c_int, c_int64_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int), value, intent(in) :: kind
      integer(c_int64_t) :: count
    end function cbr_mesh_defect_listed

    ! int cbr_mesh_get_defect(const cbr_mesh *mesh, int kind, int64_t i,
    !                         int64_t *triangles_out, int64_t *points_out);
    ! From Fortran pass both arrays: triangles(2), points(3). i is 0-based
    ! whatever the index base (it counts listed defects, it is not an id).
    function cbr_mesh_get_defect(mesh, kind, i, triangles_out, points_out) &
        bind(C, name="cbr_mesh_get_defect") result(status)
      import :: c_ptr, c_int, c_int64_t
      type(c_ptr), value, intent(in) :: mesh
      integer(c_int), value, intent(in) :: kind
      integer(c_int64_t), value, intent(in) :: i
      integer(c_int64_t), intent(out) :: triangles_out(2)
      integer(c_int64_t), intent(out) :: points_out(3)
      integer(c_int) :: status
    end function cbr_mesh_get_defect

    ! size_t strlen(const char *s);  (C library, used by cbr_f_string)
    function cbr_c_strlen(str) bind(C, name="strlen") result(length)
      import :: c_ptr, c_size_t
      type(c_ptr), value, intent(in) :: str
      integer(c_size_t) :: length
    end function cbr_c_strlen
  end interface

contains

  ! Copies the NUL-terminated C string `cstr` (e.g. the result of
  ! cbr_version, cbr_status_string or cbr_mesh_last_error) into a Fortran
  ! string of exactly its length. A null pointer gives "".
  function cbr_f_string(cstr) result(fstr)
    type(c_ptr), intent(in) :: cstr
    character(len=:), allocatable :: fstr
    character(kind=c_char), pointer :: chars(:)
    integer :: length, i

    if (.not. c_associated(cstr)) then
      fstr = ""
      return
    end if
    length = int(cbr_c_strlen(cstr))
    allocate(character(len=length) :: fstr)
    if (length == 0) return
    call c_f_pointer(cstr, chars, [length])
    do i = 1, length
      fstr(i:i) = chars(i)
    end do
  end function cbr_f_string

end module cbr
