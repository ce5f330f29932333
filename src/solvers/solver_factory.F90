!> Linear solver from its name in the deck.
!!
!! The driver asks for a solver by name and holds it as
!! `class(linear_solver_t)`; this is the one place that knows the concrete
!! types.  Names are case-insensitive: `skyline`, `dense` and, in builds with
!! them, `umfpack` and `mumps`.
!!
!! This file is preprocessed (.F90) because the UMFPACK and MUMPS solvers are
!! compiled only when CMake defines KONTAKT2D_HAVE_UMFPACK and
!! KONTAKT2D_HAVE_MUMPS.
!!
!! An MPI run of several processes (docs/parallel.md) takes part in the
!! solver's work only through MUMPS: with more than one process every other
!! solver is refused, so that only the root process ever runs an analysis.
module solver_factory
   use errors, only: status_t, STAT_INPUT
   use linear_solver, only: linear_solver_t
   use skyline_solver, only: skyline_solver_t
   use dense_solver, only: dense_solver_t
! ---------------------------------------------------------------- UMFPACK hook
! The UMFPACK solver lives in module `umfpack_solver` (src/solvers/umfpack_solver.f90,
! type `umfpack_solver_t`) and is compiled only when CMake defines
! KONTAKT2D_HAVE_UMFPACK; K2D_UMFPACK_SOLVER follows that definition.  [UMFPACK-HOOK]
#ifdef KONTAKT2D_HAVE_UMFPACK
#define K2D_UMFPACK_SOLVER 1
#else
#define K2D_UMFPACK_SOLVER 0
#endif
#if K2D_UMFPACK_SOLVER
   use umfpack_solver, only: umfpack_solver_t
#endif
#ifdef KONTAKT2D_HAVE_MUMPS
   use mumps_solver, only: mumps_solver_t
#endif
   use parallel, only: process_count
   use strings, only: itoa
   use model, only: model_t
   use contact_types, only: UPDATE_RETURN
   use run_plan, only: run_plan_t, solver_code, condense_code, scheme_code, resolve_ordering, &
         CHOICE_DECK, &
                       CHOICE_COMMAND_LINE, CHOICE_AUTOMATIC
   implicit none
   private

   public :: create_solver, solver_names, choose_solver, plan_run
   public :: AUTO_MUMPS_CONTACT_DOFS, AUTO_MUMPS_DOFS, AUTO_UMFPACK_CONTACT_DOFS, AUTO_UMFPACK_DOFS

   !> Crossovers of the automatic choice (DOFs = 2 per node, before the
   !! restraints), from the measurements of docs/performance.md: the sparse
   !! solvers win from these sizes on, the skyline solver below them.
   integer, parameter :: AUTO_MUMPS_CONTACT_DOFS = 5000     !! contact: Schur path faster
                                                            !! from the sphere at
                                                           !! a_H/5 (5 932 DOFs) on, even at 2 756
                                                           !! (punch_5_1)
   integer, parameter :: AUTO_MUMPS_DOFS = 10000            !! no contact: one MUMPS
                                                            !! solve at 1e4 DOFs takes
                                                           !! 0.019 s, the skyline's about 0.1 s
   integer, parameter :: AUTO_UMFPACK_CONTACT_DOFS = 10000  !! contact without MUMPS:
                                                            !! condensation with UMFPACK
                                                           !! 2.6 x faster at 1e4 DOFs, equal at 5
                                                           !! 932
   integer, parameter :: AUTO_UMFPACK_DOFS = 30000          !! no contact: UMFPACK faster
                                                            !! from 3e4 equations

contains

   !> The run plan of model `m` and the command line's solver `cli_solver`
   !! ('' = the deck's), all but the contact system (contact_system_kind
   !! chooses it once the equations are numbered): the solver named by -s,
   !! else by the deck's CONTROL SOLVER, else (blank or AUTO) `choose_solver`'s
   !! from the model's size and contact; the order of the equations; the
   !! contact scheme, OPTIONS CONDENSE and the automatic increments.  A name
   !! that is no solver is kept as the deck's choice with SOLVER_UNSET, for
   !! `create_solver` to refuse by its name.
   subroutine plan_run(m, cli_solver, plan, name)
      type(model_t), intent(in) :: m
      character(len=*), intent(in) :: cli_solver
      type(run_plan_t), intent(out) :: plan
      character(len=:), allocatable, intent(out) :: name   !! the solver's name as given
                                                           !! (for create_solver)
      character(len=:), allocatable :: reason
      integer :: npair
      logical :: returning
      name = 'AUTO'
      if (allocated(m%solver_name)) name = m%solver_name
      plan%solver_choice = CHOICE_DECK
      if (len_trim(cli_solver) > 0) then
         name = cli_solver
         plan%solver_choice = CHOICE_COMMAND_LINE
      end if
      npair = 0
      if (allocated(m%contact%pairs)) npair = size(m%contact%pairs)
      if (lowercase(trim(adjustl(name))) == 'auto' .or. len_trim(name) == 0) then
         call choose_solver(2*m%npoin, npair > 0, name, reason)
         plan%solver_choice = CHOICE_AUTOMATIC
         plan%solver_reason = reason
      else
         plan%solver_reason = ''
      end if
      plan%solver = solver_code(name)
      if (allocated(m%renumber)) then
         call resolve_ordering(m%renumber, plan%solver, plan%ordering, plan%ordering_reason)
      else
         call resolve_ordering('AUTO', plan%solver, plan%ordering, plan%ordering_reason)
      end if
      plan%condense = condense_code('AUTO')
      if (allocated(m%condense)) plan%condense = condense_code(m%condense)
      returning = m%contact%opts%update == UPDATE_RETURN
      plan%scheme = scheme_code(npair, returning, returning .and. m%contact%opts%modified)
      plan%autoinc = m%autoinc
   end subroutine plan_run

   !> Allocate the solver named `name` (case and surrounding blanks ignored).
   !!
   !! Unknown names give STAT_INPUT with a message that lists the valid
   !! names; `solver` is then left unallocated.
   subroutine create_solver(name, solver, status)
      character(len=*), intent(in) :: name                        !! solver name from the deck
      class(linear_solver_t), allocatable, intent(out) :: solver  !! the new, empty solver
      type(status_t), intent(inout) :: status                     !! STAT_INPUT if unknown

      if (process_count() > 1 .and. lowercase(trim(adjustl(name))) /= 'mumps') then
         call status%set(STAT_INPUT, 'linear solver "'//trim(adjustl(name))//'" cannot run on '// &
                         itoa(process_count())//' MPI processes: only "mumps" can (-s mumps)')
         return
      end if
      select case (lowercase(trim(adjustl(name))))
      case ('skyline')
         allocate (skyline_solver_t :: solver)
      case ('dense')
         allocate (dense_solver_t :: solver)
      case ('umfpack')
#if K2D_UMFPACK_SOLVER
         allocate (umfpack_solver_t :: solver)
#else
         call status%set(STAT_INPUT, 'linear solver "umfpack" is not available in this build '// &
                         '(built without UMFPACK); valid names are: '//solver_names())
#endif
      case ('mumps')
#ifdef KONTAKT2D_HAVE_MUMPS
         allocate (mumps_solver_t :: solver)
#else
         call status%set(STAT_INPUT, 'linear solver "mumps" is not available in this build '// &
                         '(built without MUMPS); valid names are: '//solver_names())
#endif
      case default
         call status%set(STAT_INPUT, 'unknown linear solver "'//trim(adjustl(name))// &
                         '"; valid names are: '//solver_names())
      end select
   end subroutine create_solver

   !> The solver of a deck that names none (SOLVER blank or AUTO) and of no
   !! -s option: MUMPS (the Schur complement of its factorization for
   !! contact) when the build has it and the model has at least
   !! AUTO_MUMPS_CONTACT_DOFS (contact) or AUTO_MUMPS_DOFS (none) DOFs, else
   !! UMFPACK from AUTO_UMFPACK_CONTACT_DOFS or AUTO_UMFPACK_DOFS, else the
   !! skyline solver; an MPI run of several processes takes MUMPS, its only
   !! solver.  `reason` says why, for the listing.
   !!
   !! Ref: docs/performance.md, "Crossover" and "Automatic choice".
   subroutine choose_solver(ndof, contact, name, reason)
      integer, intent(in) :: ndof                           !! degrees of freedom, 2 per node
      logical, intent(in) :: contact                        !! the model has contact pairs
      character(len=:), allocatable, intent(out) :: name    !! skyline, umfpack or mumps
      character(len=:), allocatable, intent(out) :: reason
      character(len=:), allocatable :: what
      logical :: mumps, umfpack
      mumps = index(solver_names(), 'mumps') > 0
      umfpack = index(solver_names(), 'umfpack') > 0
      what = merge('contact model', 'model        ', contact)
      what = trim(what)//' of '//itoa(ndof)//' DOFs'
      if (mumps .and. process_count() > 1) then
         name = 'mumps'
         reason = 'the solver of MPI runs'
      else if (mumps .and. ndof >= merge(AUTO_MUMPS_CONTACT_DOFS, AUTO_MUMPS_DOFS, contact)) then
         name = 'mumps'
         reason = what//' >= '//itoa(merge(AUTO_MUMPS_CONTACT_DOFS, AUTO_MUMPS_DOFS, contact))
      else if (umfpack .and. ndof >= merge(AUTO_UMFPACK_CONTACT_DOFS, AUTO_UMFPACK_DOFS, &
                                           contact)) then
         name = 'umfpack'
         reason = what//' >= '//itoa(merge(AUTO_UMFPACK_CONTACT_DOFS, AUTO_UMFPACK_DOFS, contact))
         if (.not. mumps) reason = reason//', built without MUMPS'
      else
         name = 'skyline'
         reason = what//' < '//itoa(merge(merge(AUTO_MUMPS_CONTACT_DOFS, AUTO_MUMPS_DOFS, &
                                                contact), &
                                          merge(AUTO_UMFPACK_CONTACT_DOFS, AUTO_UMFPACK_DOFS, &
                                                contact), mumps))
         if (.not. (mumps .or. umfpack)) reason = 'built without a sparse solver'
      end if
   end subroutine choose_solver

   !> Valid solver names of this build, comma-separated.
   pure function solver_names() result(s)
      character(len=:), allocatable :: s
      s = 'skyline, dense'
#if K2D_UMFPACK_SOLVER
      s = s//', umfpack'
#endif
#ifdef KONTAKT2D_HAVE_MUMPS
      s = s//', mumps'
#endif
   end function solver_names

   !> Lower-case copy of an ASCII string.
   pure function lowercase(s) result(r)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: r
      integer :: i, c
      r = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('A') .and. c <= iachar('Z')) r(i:i) = achar(c + 32)
      end do
   end function lowercase
end module solver_factory
