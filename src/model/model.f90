!> The analysis model: mesh, materials, boundary conditions, loads and the
!! load history, as read from the deck.  Plain data; no numerics here.
!!
!! Conventions (see docs/deck-format.md):
!! * `ntype` 1 plane stress, 2 plane strain, 3 axisymmetric (x = r, y = z).
!! * Element nodes: corners anticlockwise, then midside nodes, then the centre.
!! * Loads and prescribed displacements belong to a load case; the load history
!!   gives, for every increment, the total factor of every case.
module model
   use kinds, only: dp
   use contact_types, only: contact_def_t
   use contact_spec, only: contact_spec_t
   use pretension, only: pretension_t
   use strings, only: same_name
   implicit none
   private

   public :: model_t, material_t, restraint_t, point_load_t, edge_load_t, body_load_t, &
             node_set_t, edge_set_t, find_node_set, find_edge_set
   public :: NTYPE_PLANE_STRESS, NTYPE_PLANE_STRAIN, NTYPE_AXISYMMETRIC, ntype_name
   public :: complete_model, model_complete
   public :: MAX_NODE, MAX_CASE

   integer, parameter :: NTYPE_PLANE_STRESS = 1
   integer, parameter :: NTYPE_PLANE_STRAIN = 2
   integer, parameter :: NTYPE_AXISYMMETRIC = 3
   integer, parameter :: MAX_NODE = 9   !! largest element (Q9)
   !> Largest load case number: the factors of every case are stored per increment (and are one
   !! attribute of each increment in the result file)
   integer, parameter :: MAX_CASE = 99

   !> Isotropic linear-elastic material.
   type :: material_t
      real(dp) :: young = 0.0_dp   !! Young's modulus E
      real(dp) :: poiss = 0.0_dp   !! Poisson's ratio nu
      real(dp) :: thick = 1.0_dp   !! thickness (plane problems)
      integer :: line = 0          !! deck line, for messages
   end type material_t

   !> Restrained node: fixed or prescribed displacement components.
   type :: restraint_t
      integer :: node = 0
      logical :: fixed(2) = .false.     !! x (r) and y (z) restrained
      real(dp) :: value(2) = 0.0_dp     !! prescribed displacement at load factor 1
      integer :: icase = 1              !! load case that scales `value`
      integer :: line = 0
   end type restraint_t

   !> Concentrated nodal force (a total ring force in axisymmetry).
   type :: point_load_t
      integer :: node = 0
      real(dp) :: force(2) = 0.0_dp
      integer :: icase = 1
      integer :: line = 0
   end type point_load_t

   !> Distributed load on one element edge: normal pressure and tangential traction.
   type :: edge_load_t
      integer :: ielem = 0
      integer :: nn = 0                 !! 2 (linear edge) or 3 (quadratic edge)
      integer :: nodes(3) = 0           !! (start, end, mid) in the element's anticlockwise order
      real(dp) :: pn(3) = 0.0_dp        !! pressure at the nodes, positive compressive
      real(dp) :: pt(3) = 0.0_dp        !! tangential traction, positive from start to end
      integer :: icase = 1
      integer :: line = 0
   end type edge_load_t

   !> Uniform body force per unit volume on the elements of one material (0 = all).
   type :: body_load_t
      integer :: imat = 0
      real(dp) :: b(2) = 0.0_dp
      integer :: icase = 1
      integer :: line = 0
   end type body_load_t

   !> A named set of nodes (a gmsh physical point or curve, or a deck-defined set).
   type :: node_set_t
      character(len=:), allocatable :: name
      integer, allocatable :: nodes(:)
   end type node_set_t

   !> A named set of element edges (a gmsh physical curve): edge `iedge(k)` of
   !! element `ielem(k)`, numbered as in docs/elements.md.
   type :: edge_set_t
      character(len=:), allocatable :: name
      integer, allocatable :: ielem(:)
      integer, allocatable :: iedge(:)
   end type edge_set_t

   type :: model_t
      character(len=:), allocatable :: title
      character(len=:), allocatable :: deck_file
      integer :: ntype = NTYPE_PLANE_STRAIN
      integer :: npoin = 0
      integer :: nelem = 0
      integer :: nnode = 0              !! nodes per element declared on the control card
      integer :: nmats = 0
      integer :: ngaus = 0              !! 0 = default rule of each element
      integer :: ncase = 1              !! number of load cases
      character(len=:), allocatable :: solver_name
      ! mesh
      real(dp), allocatable :: coord(:, :)   !! (2, npoin)
      integer, allocatable :: lnods(:, :)    !! (MAX_NODE, nelem), zero padded
      integer, allocatable :: nnode_e(:)     !! nodes of each element
      integer, allocatable :: matno(:)       !! material of each element
      integer, allocatable :: node_line(:)   !! deck line of each node card
      integer, allocatable :: elem_line(:)   !! deck line of each element card
                                             !! (.msh line with a MESH block)
      integer :: restraints_line = 0         !! deck line of the RESTRAINTS keyword (for messages)
      integer, allocatable :: node_tag(:)    !! (npoin) gmsh node tags (MESH block);
                                             !! unallocated for deck meshes
      character(len=:), allocatable :: mesh_file  !! .msh file of a MESH block (''
                                                  !! or unallocated: the deck)
      ! materials, boundary conditions, loads
      type(material_t), allocatable :: mats(:)
      type(restraint_t), allocatable :: fixes(:)
      type(point_load_t), allocatable :: point_loads(:)
      type(edge_load_t), allocatable :: edge_loads(:)
      type(body_load_t), allocatable :: body_loads(:)
      ! load history: lambda(icase, i) is the total factor of case icase after increment i
      integer :: nincs = 0
      real(dp), allocatable :: lambda(:, :)  !! (ncase, 0:nincs)
      ! ties: (3, ntie) master node, slave node, dof (1 x, 2 y); slaves share the master's equation
      integer, allocatable :: ties(:, :)
      ! contact: the deck's specification as read, and the interfaces and pairs defined from it
      type(contact_spec_t) :: contact_spec
      type(contact_def_t) :: contact
      ! named sets (from gmsh physical groups or the deck)
      type(node_set_t), allocatable :: node_sets(:)
      type(edge_set_t), allocatable :: edge_sets(:)
      ! increment control: automatic cutting and growing of the deck's increments
      logical :: autoinc = .false.
      real(dp) :: autoinc_min = 1.0_dp/128.0_dp  !! smallest step, as a fraction of a deck increment
      integer :: autoinc_easy = 4                !! solutions of an easy step (the next may grow)
      ! condensation of the bodies onto the contact equations: AUTO, ON or OFF
      character(len=:), allocatable :: condense
      ! output control
      character(len=:), allocatable :: listing_level  !! FULL, SHORT or NONE
      integer :: results_every = 1                    !! result file: every n-th step and the last
      ! equation numbering: AUTO (RCM for skyline), RCM or NONE (OPTIONS RENUMBER)
      character(len=:), allocatable :: renumber
      ! pretension sections (LOADS/PRETENSION; module pretension), empty if none
      type(pretension_t), allocatable :: pretensions(:)
   end type model_t

contains

   !> Index of the node set called `name` (case-insensitive), 0 if none.
   pure integer function find_node_set(m, name) result(k)
      type(model_t), intent(in) :: m
      character(len=*), intent(in) :: name
      k = 0
      if (.not. allocated(m%node_sets)) return
      do k = 1, size(m%node_sets)
         if (same_name(m%node_sets(k)%name, name)) return
      end do
      k = 0
   end function find_node_set

   !> Index of the edge set called `name` (case-insensitive), 0 if none.
   pure integer function find_edge_set(m, name) result(k)
      type(model_t), intent(in) :: m
      character(len=*), intent(in) :: name
      k = 0
      if (.not. allocated(m%edge_sets)) return
      do k = 1, size(m%edge_sets)
         if (same_name(m%edge_sets(k)%name, name)) return
      end do
      k = 0
   end function find_edge_set


   !> Name of an analysis type, for listings and result files.
   pure function ntype_name(ntype) result(s)
      integer, intent(in) :: ntype
      character(len=:), allocatable :: s
      select case (ntype)
      case (NTYPE_PLANE_STRESS)
         s = 'plane stress'
      case (NTYPE_PLANE_STRAIN)
         s = 'plane strain'
      case (NTYPE_AXISYMMETRIC)
         s = 'axisymmetric'
      case default
         s = 'unknown'
      end select
   end function ntype_name

   !> Give a model built in code the empty parts a deck would have: no ties,
   !! no contact (interfaces, pairs, rigid bodies), condensation AUTO.
   pure subroutine complete_model(m)
      type(model_t), intent(inout) :: m
      if (.not. allocated(m%ties)) allocate (m%ties(3, 0))
      if (.not. allocated(m%contact%pairs)) allocate (m%contact%pairs(0))
      if (.not. allocated(m%contact%ifaces)) allocate (m%contact%ifaces(0))
      if (.not. allocated(m%contact%rigids)) allocate (m%contact%rigids(0))
      if (.not. allocated(m%condense)) m%condense = 'AUTO'
      if (.not. allocated(m%pretensions)) allocate (m%pretensions(0))
      m%contact%active = size(m%contact%pairs) > 0
   end subroutine complete_model

   !> Has the model the parts an analysis reads: the contact pairs and
   !! interfaces (empty without contact), and with contact the rigid bodies
   !! and the condensation choice?  (Ties may be absent: no ties.)
   pure logical function model_complete(m) result(yes)
      type(model_t), intent(in) :: m
      yes = allocated(m%contact%pairs) .and. allocated(m%contact%ifaces)
      if (.not. yes) return
      if (size(m%contact%pairs) > 0) yes = allocated(m%contact%rigids) .and. allocated(m%condense)
   end function model_complete
end module model
