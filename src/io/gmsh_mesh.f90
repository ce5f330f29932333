!> The content of a gmsh `.msh` file that Kontakt2D uses, and the element-type table.
!!
!! Owns the parsed mesh (`gmsh_mesh_t`: nodes with their tags and lines,
!! elements with their types, nodes and physical tags), the physical groups
!! (`gmsh_group_t`: appended, found by tag or by name, listed for messages),
!! the entities of a 4.1 file (`entity_t`: their physical tags), and the table
!! of the gmsh element types Kontakt2D takes (`gmsh_nnode`, `gmsh_dim`,
!! `type_name` for the message that rejects the others).  No file is read here
!! (gmsh_text, gmsh_sections) and no model is built (gmsh_reader).
!!
!! Ref: gmsh reference manual, section "MSH file format" (element types).
module gmsh_mesh
   use kinds, only: dp
   use strings, only: itoa, same_name
   use model, only: MAX_NODE
   implicit none
   private

   public :: gmsh_mesh_t, gmsh_group_t, entity_t, MAX_PHYS
   public :: alloc_nodes, alloc_elements, add_group, find_group, complete_groups
   public :: gmsh_nnode, gmsh_dim, type_name, group_by_name, group_list

   integer, parameter :: MAX_PHYS = 8   !! physical tags kept per element

   !> A physical group: dimension, tag and name ('' when the file names none).
   type :: gmsh_group_t
      integer :: dim = 0
      integer :: tag = 0
      character(len=:), allocatable :: name
   end type gmsh_group_t

   !> The content of a .msh file that Kontakt2D uses.
   type :: gmsh_mesh_t
      character(len=:), allocatable :: path
      character(len=:), allocatable :: version        !! '4.1' or '2.2'
      integer :: nnodes = 0
      integer, allocatable :: node_tag(:)             !! (nnodes)
      real(dp), allocatable :: xyz(:, :)              !! (3, nnodes)
      integer, allocatable :: node_line(:)            !! line of each node in the file
      integer :: nelems = 0
      integer, allocatable :: etype(:)                !! gmsh element type
      integer, allocatable :: enodes(:, :)            !! (MAX_NODE, nelems) node tags
      integer, allocatable :: nphys(:)                !! number of physical tags
      integer, allocatable :: ephys(:, :)             !! (MAX_PHYS, nelems) physical tags
      integer, allocatable :: eline(:)                !! line of each element in the file
      type(gmsh_group_t), allocatable :: groups(:)    !! from $PhysicalNames and the elements
   end type gmsh_mesh_t

   !> An entity of a 4.1 file: its physical tags.
   type :: entity_t
      integer :: tag = 0
      integer :: nphys = 0
      integer :: phys(MAX_PHYS) = 0
   end type entity_t

contains

   subroutine alloc_nodes(msh, n)
      type(gmsh_mesh_t), intent(inout) :: msh
      integer, intent(in) :: n
      if (allocated(msh%node_tag)) deallocate (msh%node_tag, msh%xyz, msh%node_line)
      msh%nnodes = max(n, 0)
      allocate (msh%node_tag(msh%nnodes), msh%xyz(3, msh%nnodes), msh%node_line(msh%nnodes))
      msh%node_tag = 0
      msh%xyz = 0.0_dp
      msh%node_line = 0
   end subroutine alloc_nodes

   subroutine alloc_elements(msh, n)
      type(gmsh_mesh_t), intent(inout) :: msh
      integer, intent(in) :: n
      msh%nelems = max(n, 0)
      allocate (msh%etype(msh%nelems), msh%enodes(MAX_NODE, msh%nelems), msh%nphys(msh%nelems), &
                msh%ephys(MAX_PHYS, msh%nelems), msh%eline(msh%nelems))
      msh%etype = 0
      msh%enodes = 0
      msh%nphys = 0
      msh%ephys = 0
      msh%eline = 0
   end subroutine alloc_elements

   !> Groups used by elements but absent from $PhysicalNames get their tag as name.
   subroutine complete_groups(msh)
      type(gmsh_mesh_t), intent(inout) :: msh
      integer :: k, j, dim
      logical :: found
      do k = 1, msh%nelems
         dim = gmsh_dim(msh%etype(k))
         do j = 1, msh%nphys(k)
            found = find_group(msh, dim, msh%ephys(j, k)) > 0
            if (.not. found) call add_group(msh, dim, msh%ephys(j, k), itoa(msh%ephys(j, k)))
         end do
      end do
   end subroutine complete_groups

   !> Append a physical group (component by component, see build_sets).
   subroutine add_group(msh, dim, tag, name)
      type(gmsh_mesh_t), intent(inout) :: msh
      integer, intent(in) :: dim, tag
      character(len=*), intent(in) :: name
      type(gmsh_group_t), allocatable :: tg(:)
      integer :: i
      allocate (tg(size(msh%groups) + 1))
      do i = 1, size(msh%groups)
         tg(i)%dim = msh%groups(i)%dim
         tg(i)%tag = msh%groups(i)%tag
         tg(i)%name = msh%groups(i)%name
      end do
      tg(size(tg))%dim = dim
      tg(size(tg))%tag = tag
      tg(size(tg))%name = name
      call move_alloc(tg, msh%groups)
   end subroutine add_group

   pure integer function find_group(msh, dim, tag) result(k)
      type(gmsh_mesh_t), intent(in) :: msh
      integer, intent(in) :: dim, tag
      do k = 1, size(msh%groups)
         if (msh%groups(k)%dim == dim .and. msh%groups(k)%tag == tag) return
      end do
      k = 0
   end function find_group

   !> Nodes of a gmsh element type that Kontakt2D takes (0 for any other).
   pure integer function gmsh_nnode(ety)
      integer, intent(in) :: ety
      select case (ety)
      case (15)
         gmsh_nnode = 1      ! point
      case (1)
         gmsh_nnode = 2      ! 2-node line
      case (8)
         gmsh_nnode = 3      ! 3-node line
      case (2)
         gmsh_nnode = 3      ! 3-node triangle
      case (3)
         gmsh_nnode = 4      ! 4-node quadrangle
      case (16)
         gmsh_nnode = 8      ! 8-node quadrangle
      case (10)
         gmsh_nnode = 9      ! 9-node quadrangle
      case default
         gmsh_nnode = 0
      end select
   end function gmsh_nnode

   pure integer function gmsh_dim(ety)
      integer, intent(in) :: ety
      select case (ety)
      case (15)
         gmsh_dim = 0
      case (1, 8)
         gmsh_dim = 1
      case default
         gmsh_dim = 2
      end select
   end function gmsh_dim

   pure function type_name(ety) result(s)
      integer, intent(in) :: ety
      character(len=:), allocatable :: s
      select case (ety)
      case (9)
         s = '6-node triangle: not in the element library; use 8- or 9-node quadrilaterals '// &
             '(Mesh.RecombineAll = 1) or 3-node triangles'
      case (4, 5, 6, 7, 11, 12, 13, 14, 17, 18, 19)
         s = 'a 3-D element'
      case (20:31)
         s = 'a higher-order element'
      case default
         s = 'not supported'
      end select
   end function type_name

   !> Index of the physical group of dimension dim called `name` (case-insensitive).
   integer function group_by_name(msh, dim, name) result(g)
      type(gmsh_mesh_t), intent(in) :: msh
      integer, intent(in) :: dim
      character(len=*), intent(in) :: name
      do g = 1, size(msh%groups)
         if (msh%groups(g)%dim == dim .and. same_name(msh%groups(g)%name, name)) return
      end do
      g = 0
   end function group_by_name

   !> Names of the physical groups of one dimension, quoted, for messages.
   function group_list(msh, dim) result(s)
      type(gmsh_mesh_t), intent(in) :: msh
      integer, intent(in) :: dim
      character(len=:), allocatable :: s
      integer :: g
      s = ''
      do g = 1, size(msh%groups)
         if (msh%groups(g)%dim /= dim) cycle
         if (len(s) > 0) s = s//', '
         s = s//'"'//msh%groups(g)%name//'"'
      end do
      if (len(s) == 0) s = 'none'
   end function group_list

end module gmsh_mesh
