!> LAMMPS `pair_style table` files (doc/formats.md).
!> The LAMMPS submodule of egw_table_format (src/egw/formats/table_format.f90), whose
!> interface block declares the entry points implemented here.
submodule (egw_table_format) egw_table_format_lammps
   implicit none

contains

   module procedure write_lammps
      integer :: s, i, n
      type(text_buffer) :: out
      real(dp) :: rsum, rlo, rhi, r, d, f, k, e, reach
      character(len=:), allocatable :: note

      do s = 1, size(tables)
         if (.not. allocated(tables(s)%delta)) then
            call fatal_error(error, egw_invalid_argument, "tables("//int_str(s)// &
               & "): not built or read")
            return
         end if
      end do
      if (present(units)) then
         if (len_trim(units) == 0 .or. verify(trim(units), &
            & "abcdefghijklmnopqrstuvwxyz") /= 0) then
            call fatal_error(error, egw_invalid_argument, "units = '"//units// &
               & "': must be a LAMMPS units style (lowercase letters, e.g. si)")
            return
         end if
      end if
      if (present(units)) then
         call out%add("# DATE: "//egw_version_string//" UNITS: "//trim(units)// &
            & " CONTRIBUTOR: egw")
      else
         ! lowercase on purpose: an uppercase UNITS: tag is a unit style for LAMMPS
         call out%add("# egw tables, units: those of the egw parameters (force = "// &
            & "modulus*length^2, energy = force*length)")
      end if
      call out%add("# egw "//egw_version_string//" contact force tables for "// &
         & "pair_style table (linear or spline, N >= the section's N)")
      do s = 1, size(tables)
         associate (t => tables(s))
            if (t%radius_sum > 0.0_dp) then
               rsum = t%radius_sum
               note = "R1 + R2 = "//fmt(rsum)//" (particle radii)"
            else
               rsum = 4*t%params%radius
               note = "R1 = R2 = 2R = "//fmt(2*t%params%radius)//": built from the "// &
                  & "equivalent radius R alone, distances are for two equal spheres"
            end if
            reach = t%delta_max
            if (present(delta_reach)) reach = max(reach, delta_reach)
            rlo = rsum - reach
            rhi = rsum - t%cutoff
            n = lammps_points(t, rsum, rlo, rhi)
            call out%add("")
            call out%add("# section EGW_"//int_str(s)//": model "// &
               & model_name(t%params%model)//", R = "//fmt(t%params%radius)//", E = "// &
               & fmt(t%params%modulus)//", sigma = "//fmt(t%params%sigma)//", mu = "// &
               & fmt(t%params%mu)//", psi = "//fmt(t%params%psi)//", K = "// &
               & fmt(t%params%hardness_coeff)//", rho_p = "//fmt(t%params%plastic_ratio))
            if (t%params%model == model_epgw) call out%add("# EP-GW: the LOADING "// &
               & "curve only (pair_style table is a function of r alone: no unloading "// &
               & "hysteresis, restitution 1; egw_hysteresis_* carries the dissipation)")
            call out%add("# r = R1 + R2 - delta with "//note)
            call out%add("# force = -dE/dr = P(delta) >= 0 (repulsive), zero for r > "// &
               & fmt(rhi)//" (pair cutoff); energy = int of P from the cut-off")
            call out%add("# rel_tol = "//fmt(t%rel_tol)//" relative to P_ref = "// &
               & fmt(t%reference_force))
            call out%add("# ends: r > "//fmt(rhi)//" (delta < cutoff): no force; r < "// &
               & fmt(rlo)//" (delta > "//fmt(reach)//"): LAMMPS stops with 'Pair distance "// &
               & "< table inner cutoff'")
            if (reach > t%delta_max) call out%add("# delta in ("// &
               & fmt(t%delta_max)//", "//fmt(reach)//"]: beyond the table's delta_max, "// &
               & "the deep-overlap asymptote of egw's tables (doc/theory.md 9)")
            if (t%params%model == model_epgw .and. t%params%psi > 0.0_dp) call out%add(&
               & "# EP-GW: loading curve only (pair_style table has no history: no "// &
               & "unloading hysteresis, no plastic dissipation)")
            if (rlo <= 0.0_dp) then
               call fatal_error(error, egw_invalid_argument, "delta_max = "// &
                  & format_real(reach)//": r = R1 + R2 - delta_max must be > 0")
               return
            end if
            call out%add("EGW_"//int_str(s))
            call out%add("N "//int_str(n)//" R "//fmt(rlo)//" "//fmt(rhi))
            call out%add("")
            do i = 1, n
               r = rlo + (rhi - rlo)*(i - 1)/(n - 1)
               d = rsum - r
               if (i == n) d = t%cutoff
               call table_eval(t, d, f, k)
               e = table_energy(t, d)
               if (.not. row_ok([r, e, f])) then
                  call fatal_error(error, egw_invalid_argument, "tables("//int_str(s)// &
                     & "): not finite at delta = "//format_real(d)//"; nothing written")
                  return
               end if
               call out%add(int_str(i)//" "//fmt(r)//" "//fmt(e)//" "//fmt(f))
            end do
         end associate
      end do
      call out%write(path, error)
   end procedure write_lammps

   !> Points of a LAMMPS section: doubled until the midpoint linear-interpolation error
   !> of the force is <= rel_tol * P_ref everywhere (or the point limit is reached).
   function lammps_points(t, rsum, rlo, rhi) result(n)
      type(force_table), intent(in) :: t
      real(dp), intent(in) :: rsum, rlo, rhi
      integer :: n, i
      real(dp) :: h, f0, f1, fm, k, worst
      n = 500
      do
         h = (rhi - rlo)/(n - 1)
         worst = 0
         call table_eval(t, rsum - rlo, f0, k)
         do i = 1, n - 1
            call table_eval(t, rsum - (rlo + i*h), f1, k)
            call table_eval(t, rsum - (rlo + (i - 0.5_dp)*h), fm, k)
            worst = max(worst, abs(0.5_dp*(f0 + f1) - fm))
            f0 = f1
         end do
         if (worst <= t%rel_tol*t%reference_force .or. 2*n > max_export_points) exit
         n = 2*n - 1
      end do
   end function lammps_points

end submodule egw_table_format_lammps
