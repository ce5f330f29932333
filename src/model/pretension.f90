!> Pretension sections (bolt preload): what a LOADS/PRETENSION card says and
!! what the model made of it.
!!
!! A section is a straight cut across a body, perpendicular to its axis (x or
!! y; z in axisymmetry).  Its nodes are duplicated: the elements on the side
!! of the cut towards +axis are relinked to the copies.  The copies share the
!! originals' transverse displacement (ties) and are joined to them along the
!! axis by stiff springs through one reference node (a node of no element,
!! free only along the axis):  g = u_copy - u_orig - delta, with delta the
!! reference node's axial displacement, the section's opening (negative: the
!! section shortens).  A force -F on the reference node along the axis puts
!! the tension F across the section; holding delta keeps the section's
!! shortening (the lock).  See docs/bolts.md.
module pretension
   use kinds, only: dp
   implicit none
   private
   public :: pretension_t, PRETENSION_LOCK, PRETENSION_FORCE

   integer, parameter :: PRETENSION_LOCK = 1    !! increments that hold the case's factor keep delta
   integer, parameter :: PRETENSION_FORCE = 2   !! they keep the force F * lambda instead

   type :: pretension_t
      ! as the card says
      character(len=:), allocatable :: name     !! the node set (GROUP) or the label (SECTION)
      logical :: group = .true.                 !! a node set of the mesh; else a node list followed
      integer :: axis = 2                       !! 1 x (r), 2 y (z)
      real(dp) :: force = 0.0_dp                !! preload F at factor 1 (tension positive)
      integer :: icase = 1                      !! load case whose factor scales F
      integer :: mode = PRETENSION_LOCK         !! what increments holding the factor do
      integer :: line = 0                       !! deck line of the card
      integer, allocatable :: nodes(:)          !! the section's nodes (original numbers)
      ! what the model made of it (pretension_section)
      integer, allocatable :: copies(:)         !! copy of each node (+axis side)
      integer :: ref = 0                        !! the reference node
      integer, allocatable :: plus_elems(:)     !! elements relinked to the copies (+axis side)
      integer, allocatable :: minus_elems(:)    !! elements at the cut on the -axis side
      real(dp) :: cut = 0.0_dp                  !! axial coordinate of the cut
   end type pretension_t
end module pretension
