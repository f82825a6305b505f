!> Tests of egw_params: defaults, validation messages, the mu helper.
module test_params
   use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_positive_inf
   use testdrive, only: new_unittest, unittest_type, error_type, check
   use egw, only: dp, contact_params, validate_params, egw_error, egw_ok, &
      & egw_invalid_parameter, mu_from_summits, model_epgw, model_hertz
   implicit none
   private
   public :: collect_params

contains

   subroutine collect_params(testsuite)
      type(unittest_type), allocatable, intent(out) :: testsuite(:)
      testsuite = [ &
         & new_unittest("defaults are valid", test_defaults), &
         & new_unittest("each invalid parameter is named", test_invalid), &
         & new_unittest("mu from summit density and radius", test_mu) &
         & ]
   end subroutine collect_params

   subroutine test_defaults(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      type(egw_error), allocatable :: err
      call validate_params(p, err)
      call check(error, .not. allocated(err), "default parameters must validate")
      if (allocated(error)) return
      call check(error, p%flow_pressure == 0.0_dp, "default flow_pressure must be 0")
   end subroutine test_defaults

   !> One bad value per field; the message must name the field.
   subroutine test_invalid(error)
      type(error_type), allocatable, intent(out) :: error
      type(contact_params) :: p
      real(dp) :: nan, inf
      nan = ieee_nan()
      inf = ieee_value(inf, ieee_positive_inf)
      p = contact_params(); p%model = 7;               call expect(p, "model"); if (allocated(error)) return
      p = contact_params(); p%radius = 0;              call expect(p, "radius"); if (allocated(error)) return
      p = contact_params(); p%radius = -1;             call expect(p, "radius"); if (allocated(error)) return
      p = contact_params(); p%radius = nan;            call expect(p, "radius"); if (allocated(error)) return
      p = contact_params(); p%radius = inf;            call expect(p, "radius"); if (allocated(error)) return
      p = contact_params(); p%modulus = 0;             call expect(p, "modulus"); if (allocated(error)) return
      p = contact_params(); p%modulus = nan;           call expect(p, "modulus"); if (allocated(error)) return
      p = contact_params(); p%sigma = -1e-3_dp;        call expect(p, "sigma"); if (allocated(error)) return
      p = contact_params(); p%sigma = inf;             call expect(p, "sigma"); if (allocated(error)) return
      p = contact_params(); p%sigma = 1e-3_dp; p%mu = 0; call expect(p, "mu"); if (allocated(error)) return
      p = contact_params(); p%sigma = 1e-3_dp; p%mu = nan; call expect(p, "mu"); if (allocated(error)) return
      p = contact_params(); p%psi = -1;                call expect(p, "psi"); if (allocated(error)) return
      p = contact_params(); p%psi = nan;               call expect(p, "psi"); if (allocated(error)) return
      p = contact_params(); p%hardness_coeff = 0;      call expect(p, "hardness_coeff"); if (allocated(error)) return
      p = contact_params(); p%hardness_coeff = 1;      call expect(p, "hardness_coeff"); if (allocated(error)) return
      p = contact_params(); p%hardness_coeff = nan;    call expect(p, "hardness_coeff"); if (allocated(error)) return
      p = contact_params(); p%plastic_ratio = 1;       call expect(p, "plastic_ratio"); if (allocated(error)) return
      p = contact_params(); p%plastic_ratio = nan;     call expect(p, "plastic_ratio"); if (allocated(error)) return
      ! flow_pressure: negative, NaN, +-Inf, and = modulus (the cap must lie below E*)
      block
         integer :: k
         real(dp) :: bad_py(5)
         bad_py = [-1e-3_dp, nan, inf, -inf, 1.0_dp]
         do k = 1, size(bad_py)
            p = contact_params(model=model_hertz, flow_pressure=bad_py(k))
            call expect(p, "flow_pressure"); if (allocated(error)) return
         end do
      end block
      ! the cap on a smooth sphere (Hertz, or any model with sigma = 0) is valid, and on a
      ! rough one (doc/theory.md §12 "Rough spheres with the cap")
      p = contact_params(model=model_hertz, flow_pressure=0.01_dp)
      block
         type(egw_error), allocatable :: err
         call validate_params(contact_params(sigma=1e-3_dp, mu=4.0_dp, flow_pressure=0.01_dp), &
            & err)
         call check(error, .not. allocated(err), "flow_pressure = 0.01 with EP-GW refused")
         if (allocated(error)) return
         call validate_params(p, err)
         call check(error, .not. allocated(err), "flow_pressure = 0.01 with Hertz refused")
         if (allocated(error)) return
         p%model = model_epgw
         call validate_params(p, err)
         call check(error, .not. allocated(err), "flow_pressure = 0.01, sigma = 0 refused")
         if (allocated(error)) return
      end block
      ! mu is free when the spheres are smooth
      p = contact_params(); p%sigma = 0; p%mu = 0; p%model = model_epgw
      block
         type(egw_error), allocatable :: err
         call validate_params(p, err)
         call check(error, .not. allocated(err), "mu = 0 must be accepted when sigma = 0")
      end block
   contains
      subroutine expect(params, name)
         type(contact_params), intent(in) :: params
         character(len=*), intent(in) :: name
         type(egw_error), allocatable :: err
         call validate_params(params, err)
         call check(error, allocated(err), "invalid "//name//" was accepted")
         if (allocated(error)) return
         call check(error, err%stat, egw_invalid_parameter, "status for invalid "//name)
         if (allocated(error)) return
         call check(error, index(err%message, name//" =") == 1, &
            & "message must start with the parameter name: "//err%message)
      end subroutine expect
   end subroutine test_invalid

   !> mu = (8/3) eta sigma sqrt(2 R beta): eta = 3/8, sigma = 1, R = 2, beta = 1 gives 2.
   subroutine test_mu(error)
      type(error_type), allocatable, intent(out) :: error
      call check(error, mu_from_summits(0.375_dp, 1.0_dp, 1.0_dp, 2.0_dp), 2.0_dp, &
         & thr=4*epsilon(1.0_dp), rel=.true.)
      if (allocated(error)) return
      call check(error, egw_ok, 0)
   end subroutine test_mu

   function ieee_nan() result(x)
      use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
      real(dp) :: x
      x = ieee_value(x, ieee_quiet_nan)
   end function ieee_nan

end module test_params
