! audit23: the ln P (separated tail) intervals of 1-D GW, E-GW, EP-GW tables: the stored energy
! rise (the resampled tail's integral) against the 8-point Gauss-Legendre integral of the ln P
! cubic the reader computes, over rel_tol h max P (the reader refuses > 1). Built as
! audit23_reader_margins.f90.
program stats_log
   use egw_kinds, only: dp
   use egw_status, only: egw_error
   use egw_params, only: contact_params, model_gw, model_egw, model_epgw
   use egw_rough_sphere, only: solver_options
   use egw_table
   implicit none
   type(force_table) :: t
   type(egw_error), allocatable :: err
   real(dp) :: tols(3) = [1e-2_dp, 1e-4_dp, 1e-6_dp]
   integer :: m, it, i, n, q
   integer :: models(3) = [model_gw, model_egw, model_epgw]
   real(dp) :: h, p0, p1, rise, d0, d1, c2, c3, u, w, worst
   do m = 1, 3
      do it = 1, 3
         call build_table(contact_params(model=models(m), sigma=1e-3_dp, mu=4.0_dp, psi=0.5_dp), &
            & solver_options(), -6e-3_dp, 5e-2_dp, tols(it), t, err)
         if (allocated(err)) then; print *, err%message; deallocate (err); cycle; end if
         n = size(t%delta); worst = 0
         do i = 1, t%n_log
            h = t%delta(i + 1) - t%delta(i); p0 = t%force(i); p1 = t%force(i + 1)
            rise = log(p1) - log(p0); d0 = h*t%stiffness(i)/p0; d1 = h*t%stiffness(i + 1)/p1
            c2 = 3*rise - 2*d0 - d1; c3 = d0 + d1 - 2*rise; w = 0
            do q = 1, size(gl_x)
               u = gl_x(q); w = w + gl_w(q)*exp(u*(d0 + u*(c2 + u*c3)))
            end do
            w = w*h*p0
            worst = max(worst, abs((t%energy(i + 1) - t%energy(i)) - w)/(h*max(p0, p1)*tols(it)))
         end do
         print '(a,i3,es10.2,i5,i4,a,es10.3)', "model", models(m), tols(it), n, t%n_log, &
            & "  max |dW - GL|/(rel_tol h maxP) in ln P intervals:", worst
      end do
   end do
end program stats_log
