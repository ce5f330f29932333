!> The run plan: how a run solves its model, resolved once from the deck,
!! the command line and the model's size, and read by every part that acts
!! on it (the solver and contact-system factories, the equation numbering,
!! the listing and the result file) as named integer codes, never as the
!! strings of the deck again.
!!
!! Who fills what:
!!
!!     solver, solver_choice, solver_reason   solver_factory (plan_run), before the set-up
!!     ordering, ordering_reason              plan_run (from OPTIONS RENUMBER and the solver)
!!     scheme, condense, automatic increments plan_run (from CONTACT SCHEME, OPTIONS CONDENSE,
!!                                            AUTOINC)
!!     contact_system                         contact_system_factory (contact_system_kind), once the
!!                                            equations and the contact equations are known
!!
!! The plan lives in the model layer because the outputs (io) read it through
!! `run_info_t%plan`; the names of its codes (`*_name`) are those of the
!! result file's root attributes (docs/results-format.md).
module run_plan
   use strings, only: upper
   implicit none
   private

   public :: run_plan_t
   public :: SOLVER_UNSET, SOLVER_SKYLINE, SOLVER_DENSE, SOLVER_UMFPACK, SOLVER_MUMPS
   public :: CHOICE_DECK, CHOICE_COMMAND_LINE, CHOICE_AUTOMATIC
   public :: CONDENSE_AUTO, CONDENSE_ON, CONDENSE_OFF
   public :: SYSTEM_FULL, SYSTEM_CONDENSED, SYSTEM_MUMPS_SCHUR
   public :: ORDERING_RCM, ORDERING_USER
   public :: SCHEME_NONE, SCHEME_INCREMENTAL, SCHEME_NEWTON, SCHEME_MODIFIED
   public :: solver_code, solver_name, choice_name, condense_code, system_name, ordering_name, &
         scheme_name, &
             scheme_code, resolve_ordering, plan_summary

   !> Linear solver of the bodies (deck CONTROL SOLVER, -s, or the automatic choice).
   integer, parameter :: SOLVER_UNSET = 0, SOLVER_SKYLINE = 1, SOLVER_DENSE = 2, &
         SOLVER_UMFPACK = 3, &
                         SOLVER_MUMPS = 4
   !> Who chose the solver.
   integer, parameter :: CHOICE_DECK = 1          !! CONTROL SOLVER of the deck
   integer, parameter :: CHOICE_COMMAND_LINE = 2  !! -s / --solver
   integer, parameter :: CHOICE_AUTOMATIC = 3     !! neither (SOLVER blank or AUTO):
                                                  !! model size, contact, build
   !> The deck's request for the contact system (OPTIONS CONDENSE).
   integer, parameter :: CONDENSE_AUTO = 0, CONDENSE_ON = 1, CONDENSE_OFF = 2
   !> The contact system used (the path of the contact equations).
   integer, parameter :: SYSTEM_FULL = 0          !! K_AB + K_c refactorized for
                                                  !! every new set of springs
   integer, parameter :: SYSTEM_CONDENSED = 1     !! bodies condensed onto the contact
                                                  !! equations by n_c solves
   integer, parameter :: SYSTEM_MUMPS_SCHUR = 2   !! the Schur complement of MUMPS's
                                                  !! one sparse factorization
   !> Order of the equations (OPTIONS RENUMBER, or the solver's default).
   integer, parameter :: ORDERING_RCM = 1         !! reverse Cuthill-McKee order of the node graph
   integer, parameter :: ORDERING_USER = 2        !! the user's node order (RENUMBER NONE)
   !> Contact scheme (CONTACT SCHEME / UPDATE); SCHEME_NONE without contact pairs.
   integer, parameter :: SCHEME_NONE = 0, SCHEME_INCREMENTAL = 1, SCHEME_NEWTON = 2, &
         SCHEME_MODIFIED = 3

   !> How a run solves its model.
   type :: run_plan_t
      integer :: solver = SOLVER_UNSET                !! SOLVER_*
      integer :: solver_choice = CHOICE_DECK          !! CHOICE_*
      character(len=:), allocatable :: solver_reason  !! why the automatic choice
                                                      !! took it ('' otherwise)
      integer :: condense = CONDENSE_AUTO             !! CONDENSE_*: what the deck asked for
      integer :: contact_system = SYSTEM_FULL         !! SYSTEM_*: what the run uses
      integer :: ordering = ORDERING_USER             !! ORDERING_*
      character(len=:), allocatable :: ordering_reason  !! why this order (the listing's words)
      integer :: scheme = SCHEME_NONE                 !! SCHEME_*
      logical :: autoinc = .false.                    !! automatic increments
   end type run_plan_t

contains

   !> SOLVER_* of a solver name (case and surrounding blanks ignored);
   !! SOLVER_UNSET for AUTO, blank or an unknown name.
   pure integer function solver_code(name) result(code)
      character(len=*), intent(in) :: name
      select case (upper(trim(adjustl(name))))
      case ('SKYLINE')
         code = SOLVER_SKYLINE
      case ('DENSE')
         code = SOLVER_DENSE
      case ('UMFPACK')
         code = SOLVER_UMFPACK
      case ('MUMPS')
         code = SOLVER_MUMPS
      case default
         code = SOLVER_UNSET
      end select
   end function solver_code

   !> The solver's name, lower case as the solvers name themselves ('' unset).
   pure function solver_name(code) result(s)
      integer, intent(in) :: code
      character(len=:), allocatable :: s
      select case (code)
      case (SOLVER_SKYLINE)
         s = 'skyline'
      case (SOLVER_DENSE)
         s = 'dense'
      case (SOLVER_UMFPACK)
         s = 'umfpack'
      case (SOLVER_MUMPS)
         s = 'mumps'
      case default
         s = ''
      end select
   end function solver_name

   !> 'deck', 'command line' or 'automatic'.
   pure function choice_name(code) result(s)
      integer, intent(in) :: code
      character(len=:), allocatable :: s
      select case (code)
      case (CHOICE_COMMAND_LINE)
         s = 'command line'
      case (CHOICE_AUTOMATIC)
         s = 'automatic'
      case default
         s = 'deck'
      end select
   end function choice_name

   !> CONDENSE_* of OPTIONS CONDENSE (ON, OFF; anything else, blank included, AUTO).
   pure integer function condense_code(word) result(code)
      character(len=*), intent(in) :: word
      select case (upper(trim(adjustl(word))))
      case ('ON')
         code = CONDENSE_ON
      case ('OFF')
         code = CONDENSE_OFF
      case default
         code = CONDENSE_AUTO
      end select
   end function condense_code

   !> 'full', 'condensed' or 'mumps_schur'.
   pure function system_name(code) result(s)
      integer, intent(in) :: code
      character(len=:), allocatable :: s
      select case (code)
      case (SYSTEM_CONDENSED)
         s = 'condensed'
      case (SYSTEM_MUMPS_SCHUR)
         s = 'mumps_schur'
      case default
         s = 'full'
      end select
   end function system_name

   !> 'RCM' or 'NONE' (the words of OPTIONS RENUMBER and of the listing).
   pure function ordering_name(code) result(s)
      integer, intent(in) :: code
      character(len=:), allocatable :: s
      s = merge('RCM ', 'NONE', code == ORDERING_RCM)
      s = trim(s)
   end function ordering_name

   !> 'none', 'incremental', 'newton' or 'modified'.
   pure function scheme_name(code) result(s)
      integer, intent(in) :: code
      character(len=:), allocatable :: s
      select case (code)
      case (SCHEME_INCREMENTAL)
         s = 'incremental'
      case (SCHEME_NEWTON)
         s = 'newton'
      case (SCHEME_MODIFIED)
         s = 'modified'
      case default
         s = 'none'
      end select
   end function scheme_name

   !> SCHEME_* of a model with `npair` contact pairs whose update returns to
   !! the laws (`returning`, Newton) with the stiffness kept or not (`modified`).
   pure integer function scheme_code(npair, returning, modified) result(code)
      integer, intent(in) :: npair
      logical, intent(in) :: returning, modified
      if (npair == 0) then
         code = SCHEME_NONE
      else if (.not. returning) then
         code = SCHEME_INCREMENTAL
      else if (modified) then
         code = SCHEME_MODIFIED
      else
         code = SCHEME_NEWTON
      end if
   end function scheme_code

   !> The order of the equations for OPTIONS RENUMBER `renumber` (RCM, NONE;
   !! blank or AUTO: RCM for the skyline solver, whose cost is its profile,
   !! the user's order for the others) and the solver, with the reason.
   pure subroutine resolve_ordering(renumber, solver, ordering, reason)
      character(len=*), intent(in) :: renumber
      integer, intent(in) :: solver                      !! SOLVER_*
      integer, intent(out) :: ordering                   !! ORDERING_*
      character(len=:), allocatable, intent(out) :: reason
      select case (upper(trim(adjustl(renumber))))
      case ('RCM')
         ordering = ORDERING_RCM
         reason = 'OPTIONS RENUMBER RCM'
      case ('NONE')
         ordering = ORDERING_USER
         reason = 'OPTIONS RENUMBER NONE'
      case default
         if (solver == SOLVER_SKYLINE) then
            ordering = ORDERING_RCM
            reason = 'default for the skyline solver'
         else if (solver == SOLVER_UMFPACK) then
            ordering = ORDERING_USER
            reason = 'default for UMFPACK, which orders the matrix itself'
         else
            ordering = ORDERING_USER
            reason = 'default for the '//solver_name(solver)//' solver'
         end if
      end select
   end subroutine resolve_ordering

   !> One line for the listing: "solver skyline (deck), equations RCM,
   !! contact system full, scheme newton, increments fixed".
   pure function plan_summary(p) result(s)
      type(run_plan_t), intent(in) :: p
      character(len=:), allocatable :: s
      s = 'solver '//solver_name(p%solver)//' ('//choice_name(p%solver_choice)//'), equations '// &
          ordering_name(p%ordering)//', contact system '//system_name(p%contact_system)// &
          ', scheme '// &
          scheme_name(p%scheme)//', increments '//trim(merge('automatic', 'fixed    ', p%autoinc))
   end function plan_summary
end module run_plan
