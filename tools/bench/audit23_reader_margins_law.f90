! audit23: as audit23_reader_margins.f90, for 1-D tables of Persson flat laws (H 0.8 and 0.5,
! 10 and 20 pressures a decade, 1e-2..1e-6), each written and read back
program stats_law
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params
   use egw_rough_sphere, only: solver_options
   use egw_table
   use egw_table_format, only: write_table, read_table, format_binary
   use egw_flat_law, only: table_flat_law, new_table_law
   use egw_flat_persson, only: persson_flat_curve, persson_options, self_affine_psd
   implicit none
   real(dp), parameter :: two_pi = 6.283185307179586_dp
   real(dp), allocatable :: q(:), c(:), u(:), p(:), area(:), dpdu(:)
   type(egw_error), allocatable :: e
   type(table_flat_law) :: law
   type(force_table) :: t, back
   real(dp) :: tols(3) = [1e-2_dp, 1e-4_dp, 1e-6_dp], hursts(2) = [0.8_dp, 0.5_dp]
   integer :: it, ih, pd
   do ih = 1, 2
   do pd = 1, 2
      call self_affine_psd(hursts(ih), 1.0e-6_dp, two_pi/1.0e-3_dp, two_pi/1.0e-4_dp, &
         & two_pi/1.0e-6_dp, q, c, e)
      call persson_flat_curve(q, c, 1.0e10_dp, 1.0e-9_dp*1e10_dp, 1.0e-1_dp*1e10_dp, 10*pd, &
         & persson_options(), u, p, area, dpdu, e)
      if (allocated(e)) then; print *, "persson ", e%message; stop; end if
      call new_table_law(u(size(u):1:-1), p(size(u):1:-1), law, e, dpdu=dpdu(size(u):1:-1), &
         & area=area(size(u):1:-1), modulus=1.0e10_dp)
      if (allocated(e)) then; print *, "law ", e%message; stop; end if
      do it = 1, 3
         call build_table_law(contact_params(radius=1e-3_dp, modulus=1e10_dp), law, &
            & solver_options(), -4e-6_dp, 2e-5_dp, tols(it), t, e)
         if (allocated(e)) then; print *, "build ", it, e%message; deallocate (e); cycle; end if
         call report("L", ih*100 + pd*10 + it, t)
         call write_table(t, "law.egwt", format_binary, e)
         call read_table("law.egwt", back, e)
         if (allocated(e)) then
            print *, "READ REFUSED: ", e%message; deallocate (e)
         else
            print *, "read ok"
         end if
      end do
   end do
   end do
contains
   subroutine report(tag, id, t)
      character(len=*), intent(in) :: tag
      integer, intent(in) :: id
      type(force_table), intent(in) :: t
      integer :: i, n
      real(dp) :: hh, p0, p1, d0, d1, rise, minr
      n = size(t%delta)
      minr = huge(1.0_dp)
      do i = 1, n - 1
         hh = t%delta(i + 1) - t%delta(i)
         p0 = t%force(i); p1 = t%force(i + 1)
         if (i <= t%n_log) then
            rise = log(p1) - log(p0); d0 = hh*t%stiffness(i)/p0; d1 = hh*t%stiffness(i + 1)/p1
         else
            rise = p1 - p0; d0 = hh*t%stiffness(i); d1 = hh*t%stiffness(i + 1)
         end if
         if (p1 - p0 > 1e3_dp*epsilon(1.0_dp)*p1) minr = min(minr, max(d0, d1)/rise)
      end do
      print '(a,1x,i6,1x,i5,1x,i4,1x,es10.3)', tag, id, n, t%n_log, minr
   end subroutine report
end program stats_law
