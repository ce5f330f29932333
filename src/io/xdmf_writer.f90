!> XDMF sidecar of the HDF5 result file, so that ParaView (or VisIt) opens
!! the results directly: `<results>.xdmf` next to `<results>.h5`.
!!
!! A temporal collection with one entry per finished increment.  The bodies'
!! grid shares the mesh (`/mesh/coordinates` as geometry XY and the 0-based
!! connectivity written for it in `/mesh`) and carries the nodal results of
!! its increment as point attributes: the displacement vector and the nodal
!! stresses as one 4-component attribute (xx, yy, xy, zz: the whole
!! `stress_nodal` dataset, type Matrix, so that both ParaView readers, the
!! legacy XDMF reader and the Xdmf3 readers, keep it; hyperslab columns are
!! dropped by the Xdmf3 readers), and the error estimate of its increment as
!! a cell attribute `error_indicator` (one value per element, in element
!! order, which is the order of the cells).  A mesh of one element type uses that
!! type's topology (Triangle, Quadrilateral, Quadrilateral_8,
!! Quadrilateral_9); a mixed mesh uses the Mixed topology of
!! `/mesh/cells_mixed`.  A model with contact pairs has, per increment, a
!! spatial collection of two grids: the bodies and the contact pairs (points
!! at `/contact/position`, a Polyvertex topology given inline) with the
!! pairs' results of the increment (pressure, shear, closure, slip, ...).
!! Every grid carries the load factors of its increment as a grid-centred
!! attribute `load_factor` (one tuple, one component per load case; ParaView
!! shows it as field data).  The time of increment i is i (load factors need not
!! increase).  The file is rewritten whole by results_hdf5 as increments
!! finish (not after every one in a long run: see close_increment there), so
!! it only ever names datasets that exist.
!!
!! Ref: XDMF model and format, version 2 (xdmf.org, "XDMF Model and Format").
module xdmf_writer
   use kinds, only: dp
   use strings, only: itoa, basename
   implicit none
   private
   public :: write_xdmf, xdmf_path, CELL_NAMES, CELL_NNODE, XDMF_CELL_CODE, CONTACT_ATTRIBUTES

   !> Element kinds in the order of `ncells` (and of the /mesh/cells_* datasets).
   character(len=5), parameter :: CELL_NAMES(4) = ['tri3 ', 'quad4', 'quad8', 'quad9']
   integer, parameter :: CELL_NNODE(4) = [3, 4, 8, 9]
   character(len=15), parameter :: XDMF_TYPE(4) = [character(len=15) :: 'Triangle', &
                                                   'Quadrilateral', &
                                                   'Quadrilateral_8', 'Quadrilateral_9']
   !> XDMF cell codes in a Mixed topology array.
   integer, parameter :: XDMF_CELL_CODE(4) = [4, 5, 37, 35]
   !> Datasets of /increments/NNNNN/contact shown on the contact grid (same names).
   character(len=17), parameter :: CONTACT_ATTRIBUTES(11) = &
         [character(len=17) :: 'pressure', 'shear', &
      'closure', 'slip', 'slip_irreversible', 'force_normal', 'force_tangential', 'friction', &
      'resolution', 'normal_state', 'tangential_state']
   !> The integer ones among them (state codes).
   integer, parameter :: NINT_ATTRIBUTES = 2
   character(len=*), parameter :: nl = achar(10)

contains

   !> Path of the sidecar: the result file's name with .xdmf for its extension.
   pure function xdmf_path(h5_path) result(p)
      character(len=*), intent(in) :: h5_path
      character(len=:), allocatable :: p
      integer :: k, ks
      k = index(h5_path, '.', back=.true.)
      ks = index(h5_path, '/', back=.true.)
      if (k > ks + 1) then
         p = h5_path(1:k - 1)//'.xdmf'
      else
         p = h5_path//'.xdmf'
      end if
   end function xdmf_path

   !> (Re)write the XDMF file for the increments finished so far.
   subroutine write_xdmf(path, h5_path, npoin, ncells, nmixed, incs, lambda, ierr, npair)
      character(len=*), intent(in) :: path          !! the .xdmf file
      character(len=*), intent(in) :: h5_path       !! the HDF5 result file (referenced by its name)
      integer, intent(in) :: npoin                  !! nodes
      integer, intent(in) :: ncells(4)              !! elements of each kind (CELL_NAMES)
      integer, intent(in) :: nmixed                 !! length of /mesh/cells_mixed
                                                    !! (0 if not written)
      integer, intent(in) :: incs(:)                !! finished increments
      real(dp), intent(in) :: lambda(:, :)          !! (ncase, size(incs)) load factors
      integer, intent(out) :: ierr                  !! 0, or the iostat of a failed write
      integer, intent(in), optional :: npair        !! contact pairs (0 or absent: no contact grid)
      character(len=:), allocatable :: h5, tmp, topo, pairs
      integer :: u, i, np
      character(len=16) :: grp
      integer :: pos, nbytes, k

      h5 = basename(h5_path)
      np = 0
      if (present(npair)) np = max(npair, 0)
      topo = body_topology(h5, ncells, nmixed)
      pairs = ''
      if (np > 0) pairs = pair_cells(np)
      ! write to a temporary file, then rename: a reader never sees half a file
      tmp = path//'.tmp'
      open (newunit=u, file=tmp, status='replace', action='write', access='stream', &
            form='formatted', &
            iostat=ierr)
      if (ierr /= 0) return
      write (u, '(a)', iostat=ierr) '<?xml version="1.0" ?>'//nl// &
         '<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>'//nl// &
         '<Xdmf Version="2.0" xmlns:xi="http://www.w3.org/2001/XInclude">'//nl// &
         '  <Domain>'//nl// &
         '    <Grid Name="Kontakt2D" GridType="Collection" CollectionType="Temporal">'
      do i = 1, size(incs)
         if (ierr /= 0) exit
         write (grp, '(i5.5)') incs(i)
         if (np > 0) then
            write (u, '(a)', iostat=ierr) '      <Grid Name="increment '//trim(grp)// &
               '" GridType="Collection" CollectionType="Spatial">'//nl// &
               '        <Time Value="'//itoa(incs(i))//'" />'//nl// &
               body_grid(h5, grp, npoin, sum(ncells), topo, lambda(:, i), '', 'bodies')//nl// &
               contact_grid(h5, grp, np, pairs, lambda(:, i))//nl//'      </Grid>'
         else
            write (u, '(a)', iostat=ierr) body_grid(h5, grp, npoin, sum(ncells), topo, lambda(:, &
                                                                                              i), &
               '        <Time Value="'//itoa(incs(i))//'" />'//nl, 'increment '//trim(grp))
         end if
      end do
      if (ierr == 0) write (u, '(a)', iostat=ierr) '    </Grid>'//nl//'  </Domain>'//nl//'</Xdmf>'
      if (ierr /= 0) then
         close (u, status='delete')
         return
      end if
      ! gfortran reports no error when a formatted write or a close meets a full
      ! disk: the size of the closed file is compared with the position written
      inquire (unit=u, pos=pos)
      close (u, iostat=ierr)
      nbytes = -1
      inquire (file=tmp, size=nbytes)
      if (ierr == 0 .and. nbytes < pos - 1) ierr = -1
      if (ierr /= 0) then
         open (newunit=u, file=tmp, status='old', action='readwrite', iostat=k)
         if (k == 0) close (u, status='delete')
         return
      end if
      call rename_file(tmp, path, ierr)
   end subroutine write_xdmf

   !> The Topology element of the bodies' mesh.
   function body_topology(h5, ncells, nmixed) result(s)
      character(len=*), intent(in) :: h5            !! name of the HDF5 file
      integer, intent(in) :: ncells(4)              !! elements of each kind
      integer, intent(in) :: nmixed                 !! length of /mesh/cells_mixed
      character(len=:), allocatable :: s
      integer :: k, kind_used
      kind_used = 0
      do k = 1, 4
         if (ncells(k) > 0) kind_used = k
      end do
      if (count(ncells > 0) == 1) then
         s = '        <Topology TopologyType="'//trim(XDMF_TYPE(kind_used))// &
             '" NumberOfElements="'//itoa(ncells(kind_used))//'">'//nl// &
             '          <DataItem Dimensions="'//itoa(ncells(kind_used))//' '// &
             itoa(CELL_NNODE(kind_used))// &
             '" NumberType="Int" Precision="4" Format="HDF">'//h5//':/mesh/cells_'// &
             trim(CELL_NAMES(kind_used))//'</DataItem>'//nl//'        </Topology>'
      else
         s = '        <Topology TopologyType="Mixed" NumberOfElements="'//itoa(sum(ncells))// &
               '">'//nl// &
             '          <DataItem Dimensions="'//itoa(nmixed)// &
             '" NumberType="Int" Precision="4" '// &
             'Format="HDF">'//h5//':/mesh/cells_mixed</DataItem>'//nl//'        </Topology>'
      end if
   end function body_topology

   !> The uniform grid of the bodies in one increment.
   function body_grid(h5, grp, npoin, nelem, topo, lambda, time, name) result(s)
      character(len=*), intent(in) :: h5            !! name of the HDF5 file
      character(len=*), intent(in) :: grp           !! the increment's group name (NNNNN)
      integer, intent(in) :: npoin                  !! nodes
      integer, intent(in) :: nelem                  !! elements (cells)
      character(len=*), intent(in) :: topo          !! the Topology element
      real(dp), intent(in) :: lambda(:)             !! load factors of the increment
      character(len=*), intent(in) :: time          !! the Time element ('' inside
                                                    !! a spatial collection)
      character(len=*), intent(in) :: name          !! the grid's name
      character(len=:), allocatable :: s
      s = '      <Grid Name="'//name//'" GridType="Uniform">'//nl//time//topo//nl// &
          '        <Geometry GeometryType="XY">'//nl// &
          '          '//hdf_item(h5, '/mesh/coordinates', itoa(npoin)//' 2', .false.)//nl// &
          '        </Geometry>'//nl// &
          attribute('displacement', 'Vector', hdf_item(h5, &
                                                       '/increments/'//trim(grp)// &
                                                       '/displacement_xyz', &
                                                       itoa(npoin)//' 3', .false.))//nl// &
          attribute('stress', 'Matrix', hdf_item(h5, '/increments/'//trim(grp)//'/stress_nodal', &
                                                 itoa(npoin)//' 4', .false.))//nl// &
          attribute('error_indicator', 'Scalar', hdf_item(h5, &
                                                          '/increments/'//trim(grp)// &
                                                          '/error_indicator', &
                                                          itoa(nelem), .false.), 'Cell')//nl// &
          load_factor_attribute(lambda)//nl//'      </Grid>'
   end function body_grid

   !> The uniform grid of the contact pairs in one increment: one vertex per
   !! pair at its position, the pair results as point attributes.
   function contact_grid(h5, grp, npair, pairs, lambda) result(s)
      character(len=*), intent(in) :: h5            !! name of the HDF5 file
      character(len=*), intent(in) :: grp           !! the increment's group name (NNNNN)
      integer, intent(in) :: npair                  !! contact pairs
      character(len=*), intent(in) :: pairs         !! the pairs' vertex list (pair_cells)
      real(dp), intent(in) :: lambda(:)             !! load factors of the increment
      character(len=:), allocatable :: s
      integer :: k
      s = '      <Grid Name="contact" GridType="Uniform">'//nl// &
          '        <Topology TopologyType="Polyvertex" NumberOfElements="'//itoa(npair)// &
          '" NodesPerElement="1">'//nl//'          '//pairs//nl//'        </Topology>'//nl// &
          '        <Geometry GeometryType="XY">'//nl// &
          '          '//hdf_item(h5, '/contact/position', itoa(npair)//' 2', .false.)//nl// &
          '        </Geometry>'
      do k = 1, size(CONTACT_ATTRIBUTES)
         s = s//nl//attribute(trim(CONTACT_ATTRIBUTES(k)), 'Scalar', &
                              hdf_item(h5, '/increments/'//trim(grp)//'/contact/'// &
                                       trim(CONTACT_ATTRIBUTES(k)), &
                                       itoa(npair), k > size(CONTACT_ATTRIBUTES) - NINT_ATTRIBUTES))
      end do
      s = s//nl//load_factor_attribute(lambda)//nl//'      </Grid>'
   end function contact_grid

   !> The inline vertex list 0 .. npair-1 of the contact grid (the Xdmf3
   !! readers make no cells of a Polyvertex topology without one).
   function pair_cells(npair) result(s)
      integer, intent(in) :: npair                  !! contact pairs
      character(len=:), allocatable :: s
      character(len=12) :: b
      integer :: j
      s = '<DataItem Dimensions="'//itoa(npair)//' 1" NumberType="Int" Precision="4" Format="XML">'
      do j = 0, npair - 1
         write (b, '(i0)') j
         if (j > 0) s = s//' '
         s = s//trim(b)
      end do
      s = s//'</DataItem>'
   end function pair_cells

   !> A DataItem naming a dataset of the HDF5 file.
   pure function hdf_item(h5, dset, dims, int4) result(s)
      character(len=*), intent(in) :: h5            !! name of the HDF5 file
      character(len=*), intent(in) :: dset          !! the dataset's path in the file
      character(len=*), intent(in) :: dims          !! its dimensions, row-major
      logical, intent(in) :: int4                   !! 32-bit integers (else 64-bit reals)
      character(len=:), allocatable :: s
      if (int4) then
         s = '<DataItem Dimensions="'//dims//'" NumberType="Int" Precision="4" Format="HDF">'// &
               h5//':'//dset// &
             '</DataItem>'
      else
         s = '<DataItem Dimensions="'//dims// &
               '" NumberType="Float" Precision="8" Format="HDF">'//h5//':'//dset// &
             '</DataItem>'
      end if
   end function hdf_item

   !> A node-centred (or `center`-centred) Attribute element around one DataItem.
   pure function attribute(name, kind, item, center) result(s)
      character(len=*), intent(in) :: name          !! the attribute's name
      character(len=*), intent(in) :: kind          !! Scalar, Vector or Matrix
      character(len=*), intent(in) :: item          !! its DataItem
      character(len=*), intent(in), optional :: center  !! Cell (default Node)
      character(len=:), allocatable :: s, c
      c = 'Node'
      if (present(center)) c = center
      s = '        <Attribute Name="'//name//'" AttributeType="'//kind//'" Center="'//c//'">'// &
            nl// &
          '          '//item//nl//'        </Attribute>'
   end function attribute

   !> The load factors of an increment as a grid-centred attribute, given
   !! inline: one tuple of one component per load case (type Matrix 1 x ncase,
   !! which the legacy and the Xdmf3 readers read alike; a Scalar of several
   !! values is several tuples in one and several components in the other).
   function load_factor_attribute(lambda) result(s)
      real(dp), intent(in) :: lambda(:)             !! load factors of the increment
      character(len=:), allocatable :: s
      s = '        <Attribute Name="load_factor" AttributeType="Matrix" Center="Grid">'//nl// &
          '          <DataItem Dimensions="1 '//itoa(size(lambda))// &
          '" NumberType="Float" Precision="8" '// &
          'Format="XML">'//factors(lambda)//'</DataItem>'//nl//'        </Attribute>'
   end function load_factor_attribute

   !> Load factors as "l1 l2 ...".
   function factors(l) result(s)
      real(dp), intent(in) :: l(:)
      character(len=:), allocatable :: s
      character(len=32) :: b
      integer :: k
      s = ''
      do k = 1, size(l)
         write (b, '(es25.17)') l(k)
         if (k > 1) s = s//' '
         s = s//trim(adjustl(b))
      end do
   end function factors

   !> rename(2) through the C library: atomic replacement of the old sidecar.
   subroutine rename_file(from, to, ierr)
      use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
      character(len=*), intent(in) :: from, to
      integer, intent(out) :: ierr
      interface
         integer(c_int) function c_rename(old, new) bind(C, name='rename')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: old(*), new(*)
         end function c_rename
      end interface
      ierr = int(c_rename(from//c_null_char, to//c_null_char))
   end subroutine rename_file
end module xdmf_writer
