!> Contact system from the deck's choice (OPTIONS CONDENSE) and the solver,
!! chosen once.
!!
!! The one place that knows the concrete contact systems: the driver holds
!! the result as class(contact_system_t).  A new way of solving the contact
!! system is a new type extending contact_system_t and one more case here.
!!
!! The choice (measured crossovers: docs/performance.md, "Automatic choice"):
!! * without contact, or CONDENSE OFF: the full system (refactorize K_AB + K_c
!!   for every new set of springs);
!! * with the MUMPS solver, CONDENSE ON: the Schur complement from MUMPS's
!!   factorization (mumps_schur_system), one sparse factorization for the
!!   whole run; AUTO takes it when its work per new set of springs, a dense
!!   Cholesky factorization of the n_c contact equations, costs no more than
!!   the full system's, a sparse factorization of the neq equations
!!   (`schur_pays`), else the full system;
!! * with another solver, CONDENSE ON, or AUTO up to
!!   AUTO_MAX_CONTACT_EQUATIONS contact equations: the condensation by n_c
!!   solves (condensed_system).
!! AUTO never condenses beyond AUTO_MAX_CONTACT_EQUATIONS with the condensation
!! by solves, nor beyond AUTO_MAX_SCHUR_EQUATIONS with MUMPS's Schur complement
!! (the dense system of the contact equations grows as n_c^2 in memory, n_c^3
!! in work), and the Schur complement needs at least one equation off the
!! contact equations (ON falls back to the condensation by solves).
!!
!! This file is preprocessed (.F90): the MUMPS system is compiled only when
!! CMake defines KONTAKT2D_HAVE_MUMPS.
module contact_system_factory
   use kinds, only: dp
   use run_plan, only: CONDENSE_ON, CONDENSE_OFF, SYSTEM_FULL, SYSTEM_CONDENSED, SYSTEM_MUMPS_SCHUR
   use linear_solver, only: linear_solver_t
   use contact_system, only: contact_system_t
   use kept_factor_system, only: kept_factor_system_t
   use condensed_system, only: condensed_system_t
#ifdef KONTAKT2D_HAVE_MUMPS
   use mumps_solver, only: mumps_solver_t
   use mumps_schur_system, only: mumps_schur_system_t
#endif
   implicit none
   private
   public :: create_contact_system, contact_system_kind, schur_pays, AUTO_MAX_CONTACT_EQUATIONS, &
             AUTO_MAX_SCHUR_EQUATIONS

   !> CONDENSE AUTO condenses up to this many contact equations (the dense
   !! system of the contact equations grows as n_c^2 in memory, n_c^3 in work).
   integer, parameter :: AUTO_MAX_CONTACT_EQUATIONS = 1500
   !> With the MUMPS solver AUTO weighs the Schur complement against the full
   !! system (`schur_pays`) up to this many contact equations: its dense
   !! arrays take about 40 n_c^2 bytes (S, S's factor, V, F^-1, F^-1 + D:
   !! 0.65 GB measured at 4 002, 1.4 GB at this limit), and beyond it the full
   !! system is taken whatever the model's size (measured, issue 28: 1 001
   !! pairs, 4 002 contact equations, on 1e5 DOFs, the Schur path in 16.7 s
   !! against 115 s for the full system; 3 001 pairs, 12 002 contact equations,
   !! on 1.9e4 DOFs more than 100 s by the 8th of 50 increments, where the full
   !! system takes about 30 s).
   integer, parameter :: AUTO_MAX_SCHUR_EQUATIONS = 6000

   !> The measured costs behind `schur_pays` (docs/performance.md, "Automatic
   !! choice"; CPU seconds, one core, OpenBLAS): one MUMPS factorization of
   !! the punch-on-foundation meshes takes T_SPARSE (neq/1e4)^SPARSE_EXPONENT
   !! (1e4 to 1e6 equations) and its solve about SOLVE_SHARE of that; a new
   !! set of springs on n_c contact equations and a solve with them, in the
   !! springs' own coordinates (contact_projection) with one refinement step,
   !! T_DENSE (n_c/1202)^3 (3.5 ms + 3 x 1.5 ms at 1 202).
   real(dp), parameter :: T_SPARSE = 0.016_dp, SPARSE_EXPONENT = 1.24_dp, SOLVE_SHARE = 0.2_dp, &
                          T_DENSE = 0.008_dp

contains

   !> The contact system (SYSTEM_* of run_plan, for `run_plan_t%contact_system`)
   !! for OPTIONS CONDENSE `condense` (CONDENSE_*) and the bodies' solver
   !! (when given: the MUMPS solver condenses through its Schur complement).
   function contact_system_kind(condense, npair, nc, solver) result(kind)
      integer, intent(in) :: condense          !! CONDENSE_AUTO, CONDENSE_ON or CONDENSE_OFF
      integer, intent(in) :: npair             !! contact pairs
      integer, intent(in) :: nc                !! contact equations (distinct
                                               !! free equations of the pairs)
      class(linear_solver_t), intent(in), optional :: solver   !! the bodies' solver,
                                                               !! analysed (neq known)
      integer :: kind, neq
      logical :: mumps
      mumps = .false.
      neq = 0
#ifdef KONTAKT2D_HAVE_MUMPS
      if (present(solver)) then
         neq = solver%neq
         select type (solver)
         type is (mumps_solver_t)
            mumps = nc > 0 .and. nc < solver%neq
         end select
      end if
#endif
      kind = SYSTEM_FULL
      if (npair > 0) then
         select case (condense)
         case (CONDENSE_ON)
            kind = merge(SYSTEM_MUMPS_SCHUR, SYSTEM_CONDENSED, mumps)
         case (CONDENSE_OFF)
            kind = SYSTEM_FULL
         case default
            if (mumps) then
               if (nc <= AUTO_MAX_SCHUR_EQUATIONS) then
                  kind = merge(SYSTEM_MUMPS_SCHUR, SYSTEM_FULL, schur_pays(neq, nc))
               end if
            else if (nc <= AUTO_MAX_CONTACT_EQUATIONS) then
               kind = SYSTEM_CONDENSED
            end if
         end select
      end if
   end function contact_system_kind

   !> The contact system of kind `kind` (SYSTEM_*, from contact_system_kind).
   subroutine create_contact_system(kind, sys)
      integer, intent(in) :: kind
      class(contact_system_t), allocatable, intent(out) :: sys
      select case (kind)
#ifdef KONTAKT2D_HAVE_MUMPS
      case (SYSTEM_MUMPS_SCHUR)
         allocate (mumps_schur_system_t :: sys)
#endif
      case (SYSTEM_CONDENSED)
         allocate (condensed_system_t :: sys)
      case default
         allocate (kept_factor_system_t :: sys)
      end select
   end subroutine create_contact_system

   !> Does the Schur complement pay for a model of neq equations, nc of them
   !! contact equations?  Both it and the full system factorize once per new
   !! set of springs and solve, densely on the nc contact equations or
   !! sparsely on all neq: the Schur complement when the dense work costs no
   !! more than the sparse factorization and solve.
   pure logical function schur_pays(neq, nc)
      integer, intent(in) :: neq, nc
      schur_pays = T_DENSE*(real(nc, dp)/1202.0_dp)**3 <= &
                   (1.0_dp + SOLVE_SHARE)*T_SPARSE*(real(neq, dp)/1.0e4_dp)**SPARSE_EXPONENT
   end function schur_pays
end module contact_system_factory
