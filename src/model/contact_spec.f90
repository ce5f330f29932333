!> The contact specification as the deck gives it: surfaces, explicit pairs,
!! the interface laws in their input units, rigid bodies and the algorithm
!! options.
!!
!! The deck reader (io/deck_contact) fills it and returns; nothing here is
!! computed.  The contact definition (contact/contact_definition), run after
!! reading, builds from it the pairs, lumped areas and per-pair R and converts
!! the constants to model units, into the model's `contact` (contact_types).
!! Every item keeps its deck line, so that the definition reports its
!! problems at `file:line` like the reader.
module contact_spec
   use kinds, only: dp
   use contact_types, only: interface_t, rigid_body_t, contact_options_t
   implicit none
   private

   public :: surface_spec_t, pair_spec_t, iface_spec_t, contact_spec_t, is_rigid_reference

   !> A surface as the deck gives it (SURFACE card): a set name, or a list of nodes.
   type :: surface_spec_t
      character(len=:), allocatable :: set_name   !! node or edge set (columns 21-);
                                                  !! unallocated: a node list
      integer, allocatable :: nodes(:)            !! the listed nodes (data cards after SURFACE)
      integer :: line = 0                         !! deck line of the SURFACE card
      logical :: given = .false.
   end type surface_spec_t

   !> One explicit pair (a data card after PAIRS).
   type :: pair_spec_t
      integer :: node_a = 0
      integer :: node_b = 0
      real(dp) :: g0 = 0.0_dp          !! initial gap [model length]
      real(dp) :: alpha = 0.0_dp       !! angle of the tangent t to the x axis [degrees]
      real(dp) :: area = 0.0_dp        !! contact area [model length^2]
      logical :: has_g0 = .false.      !! G0 given (else from the coordinates)
      logical :: has_alpha = .false.   !! ALPHA given (else the normal of surface B)
      logical :: has_area = .false.    !! AREA given (else lumped from surface B)
      integer :: line = 0
   end type pair_spec_t

   !> What the deck says about one interface, before the pairs are built.
   type :: iface_spec_t
      type(interface_t) :: law                   !! law, constants in input units
                                                 !! (the *_in fields), options
      type(surface_spec_t) :: surf(2)            !! A, B
      type(pair_spec_t), allocatable :: pairs(:) !! explicit pairs (PAIRS)
      logical :: have_normal = .false.           !! a NORMAL card was given
      logical :: have_friction = .false.         !! a FRICTION card was given
      logical :: have_matching = .false.         !! a MATCHING card was given
      integer :: line = 0                        !! deck line of the INTERFACE (or first) card
      integer :: matching_line = 0
   end type iface_spec_t

   !> The CONTACT block.
   type :: contact_spec_t
      logical :: given = .false.       !! the deck has a CONTACT block and it was read
      logical :: complete = .false.    !! read without errors (nor any
                                       !! before it): ready to be defined
      integer :: line = 0              !! deck line of the CONTACT keyword
      type(iface_spec_t), allocatable :: ifaces(:)
      type(rigid_body_t), allocatable :: rigids(:)
      type(contact_options_t) :: opts  !! algorithm options (AUGMENTED, UPDATE, CONVERGE, ...)
   end type contact_spec_t

contains

   !> Is node ip the reference node of a rigid body of the specification?
   pure logical function is_rigid_reference(cs, ip)
      type(contact_spec_t), intent(in) :: cs
      integer, intent(in) :: ip       !! node number
      is_rigid_reference = .false.
      if (.not. allocated(cs%rigids)) return
      if (size(cs%rigids) == 0) return
      is_rigid_reference = any(cs%rigids%node == ip)
   end function is_rigid_reference
end module contact_spec
