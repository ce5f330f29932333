!> Contact system from the deck's choice (OPTIONS CONDENSE), chosen once.
!!
!! The one place that knows the concrete contact systems: the driver holds
!! the result as class(contact_system_t).  A new way of solving the contact
!! system is a new type extending contact_system_t and one more case here.
module contact_system_factory
   use strings, only: upper
   use contact_system, only: contact_system_t
   use full_system, only: full_system_t
   use condensed_system, only: condensed_system_t
   implicit none
   private
   public :: create_contact_system, AUTO_MAX_CONTACT_EQUATIONS

   !> CONDENSE AUTO condenses up to this many contact equations (the dense
   !! system of the contact equations grows as n_c^2 in memory, n_c^3 in work).
   integer, parameter :: AUTO_MAX_CONTACT_EQUATIONS = 1500

   contains

   !> The contact system for OPTIONS CONDENSE `condense` (ON, OFF or AUTO,
   !! case-insensitive; anything else is AUTO): condensed for a contact model
   !! when ON, or when AUTO and there are at most AUTO_MAX_CONTACT_EQUATIONS
   !! contact equations; otherwise (and always without contact) the full system.
   subroutine create_contact_system(condense, npair, nc, sys)
      character(len=*), intent(in) :: condense
      integer, intent(in) :: npair            !! contact pairs
      integer, intent(in) :: nc               !! contact equations (distinct free equations of the pairs)
      class(contact_system_t), allocatable, intent(out) :: sys
      logical :: condensed
      condensed = .false.
      if (npair > 0) then
         select case (upper(trim(adjustl(condense))))
         case ('ON')
            condensed = .true.
         case ('OFF')
            condensed = .false.
         case default
            condensed = nc <= AUTO_MAX_CONTACT_EQUATIONS
         end select
      end if
      if (condensed) then
         allocate (condensed_system_t :: sys)
      else
         allocate (full_system_t :: sys)
      end if
   end subroutine create_contact_system
end module contact_system_factory
