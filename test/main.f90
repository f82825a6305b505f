!> Runs every egw test suite, or one suite (`fpm test -- suite`), or one test
!> of one suite (`fpm test -- suite test`). Ends with "N passed, N failed".
program tester
   use, intrinsic :: iso_fortran_env, only: error_unit, output_unit
   use testdrive, only: run_testsuite, run_selected, new_testsuite, testsuite_type, &
      & select_suite, unittest_type
   use test_params, only: collect_params
   use test_ellip, only: collect_ellip
   use test_hertz, only: collect_hertz
   use test_gauss, only: collect_gauss
   use test_asperity, only: collect_asperity
   use test_halfspace, only: collect_halfspace
   use test_rough_sphere, only: collect_rough_sphere
   use test_table, only: collect_table
   use test_table_format, only: collect_table_format
   use test_capi, only: collect_capi
   use test_capi_structs, only: collect_capi_structs
   use test_capi_table, only: collect_capi_table
   use test_capi_io, only: collect_capi_io
   use test_text_io, only: collect_text_io
   use test_scene, only: collect_scene
   use test_capi_scene, only: collect_capi_scene
   use test_stability, only: collect_stability
   use test_unloading, only: collect_unloading
   use test_cli, only: collect_cli
   use test_hysteresis, only: collect_hysteresis
   use test_hysteresis_energy, only: collect_hysteresis_energy
   use test_unload_sphere, only: collect_unload_sphere
   use test_input, only: collect_input
   use test_facade, only: collect_facade
   use test_cache, only: collect_cache
   use test_capi_array, only: collect_capi_array
   use test_flat_law, only: collect_flat_law
   use test_flat_bem, only: collect_flat_bem
   use test_cap_sphere, only: collect_cap_sphere
   use test_cap_hysteresis, only: collect_cap_hysteresis
   use test_rough_cap, only: collect_rough_cap
   use test_rough_cap_hysteresis, only: collect_rough_cap_hysteresis
   use test_search, only: collect_search
   implicit none
   type(testsuite_type), allocatable :: suites(:)
   type(unittest_type), allocatable :: tests(:)
   character(len=:), allocatable :: suite_name, test_name
   integer :: stat, is, ntotal

   suites = [ &
      & new_testsuite("params", collect_params), &
      & new_testsuite("search", collect_search), &
      & new_testsuite("flat_law", collect_flat_law), &
      & new_testsuite("ellip", collect_ellip), &
      & new_testsuite("hertz", collect_hertz), &
      & new_testsuite("gauss", collect_gauss), &
      & new_testsuite("asperity", collect_asperity), &
      & new_testsuite("halfspace", collect_halfspace), &
      & new_testsuite("rough_sphere", collect_rough_sphere), &
      & new_testsuite("table", collect_table), &
      & new_testsuite("table_format", collect_table_format), &
      & new_testsuite("capi", collect_capi), &
      & new_testsuite("capi_structs", collect_capi_structs), &
      & new_testsuite("capi_table", collect_capi_table), &
      & new_testsuite("capi_io", collect_capi_io), &
      & new_testsuite("text_io", collect_text_io), &
      & new_testsuite("scene", collect_scene), &
      & new_testsuite("capi_scene", collect_capi_scene), &
      & new_testsuite("stability", collect_stability), &
      & new_testsuite("unloading", collect_unloading), &
      & new_testsuite("cli", collect_cli), &
      & new_testsuite("unload_sphere", collect_unload_sphere), &
      & new_testsuite("hysteresis", collect_hysteresis), &
      & new_testsuite("hysteresis_energy", collect_hysteresis_energy), &
      & new_testsuite("input", collect_input), &
      & new_testsuite("facade", collect_facade), &
      & new_testsuite("capi_array", collect_capi_array), &
      & new_testsuite("cache", collect_cache), &
      & new_testsuite("flat_bem", collect_flat_bem), &
      & new_testsuite("cap_sphere", collect_cap_sphere), &
      & new_testsuite("cap_hysteresis", collect_cap_hysteresis), &
      & new_testsuite("rough_cap", collect_rough_cap), &
      & new_testsuite("rough_cap_hysteresis", collect_rough_cap_hysteresis) &
      & ]

   stat = 0
   ntotal = 0
   if (command_argument_count() >= 1) then
      call get_arg(1, suite_name)
      is = select_suite(suites, suite_name)
      if (is < 1) then
         write (error_unit, '(a)') "unknown suite '"//suite_name//"'; suites are:"
         do is = 1, size(suites)
            write (error_unit, '(2x,a)') suites(is)%name
         end do
         error stop 1
      end if
      write (output_unit, '(a)') "# suite "//suites(is)%name
      if (command_argument_count() >= 2) then
         call get_arg(2, test_name)
         call run_selected(suites(is)%collect, test_name, output_unit, stat)
         ntotal = 1
      else
         call run_testsuite(suites(is)%collect, output_unit, stat)
         call suites(is)%collect(tests)
         ntotal = size(tests)
      end if
   else
      do is = 1, size(suites)
         write (output_unit, '(a)') "# suite "//suites(is)%name
         call run_testsuite(suites(is)%collect, output_unit, stat)
         call suites(is)%collect(tests)
         ntotal = ntotal + size(tests)
      end do
   end if

   write (output_unit, '(i0,a,i0,a)') ntotal - stat, " passed, ", stat, " failed"
   if (stat > 0) error stop 1

contains

   subroutine get_arg(i, arg)
      integer, intent(in) :: i
      character(len=:), allocatable, intent(out) :: arg
      integer :: n
      call get_command_argument(i, length=n)
      allocate (character(len=n) :: arg)
      call get_command_argument(i, arg)
   end subroutine get_arg

end program tester
