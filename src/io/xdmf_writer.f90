!> XDMF sidecar of the HDF5 result file, so that ParaView (or VisIt) opens
!! the results directly: `<results>.xdmf` next to `<results>.h5`.
!!
!! A temporal collection with one uniform grid per finished increment; every
!! grid shares the mesh (`/mesh/coordinates` as geometry XY and the 0-based
!! connectivity written for it in `/mesh`) and carries the nodal results of
!! its increment as point attributes: the displacement vector and the four
!! nodal stress components (hyperslabs of `stress_nodal`).  A mesh of one
!! element type uses that type's topology (Triangle, Quadrilateral,
!! Quadrilateral_8, Quadrilateral_9); a mixed mesh uses the Mixed topology
!! of `/mesh/cells_mixed`.  The file is rewritten after every increment, so
!! it only ever names datasets that exist.  The time of grid i is i (the
!! increment number: load factors need not increase); the load factors are
!! given as Information.
!!
!! Ref: XDMF model and format, version 2 (xdmf.org, "XDMF Model and Format").
module xdmf_writer
   use kinds, only: dp
   use strings, only: itoa, basename
   implicit none
   private
   public :: write_xdmf, xdmf_path, CELL_NAMES, CELL_NNODE, XDMF_CELL_CODE

   !> Element kinds in the order of `ncells` (and of the /mesh/cells_* datasets).
   character(len=5), parameter :: CELL_NAMES(4) = ['tri3 ', 'quad4', 'quad8', 'quad9']
   integer, parameter :: CELL_NNODE(4) = [3, 4, 8, 9]
   character(len=15), parameter :: XDMF_TYPE(4) = [character(len=15) :: 'Triangle', 'Quadrilateral', &
                                                   'Quadrilateral_8', 'Quadrilateral_9']
   !> XDMF cell codes in a Mixed topology array.
   integer, parameter :: XDMF_CELL_CODE(4) = [4, 5, 37, 35]

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
   subroutine write_xdmf(path, h5_path, npoin, ncells, nmixed, incs, lambda, ierr)
      character(len=*), intent(in) :: path          !! the .xdmf file
      character(len=*), intent(in) :: h5_path       !! the HDF5 result file (referenced by its name)
      integer, intent(in) :: npoin                  !! nodes
      integer, intent(in) :: ncells(4)              !! elements of each kind (CELL_NAMES)
      integer, intent(in) :: nmixed                 !! length of /mesh/cells_mixed (0 if not written)
      integer, intent(in) :: incs(:)                !! finished increments
      real(dp), intent(in) :: lambda(:, :)          !! (ncase, size(incs)) load factors
      integer, intent(out) :: ierr                  !! 0, or the iostat of a failed write
      character(len=:), allocatable :: h5, tmp
      integer :: u, i, k, kind_used, ntypes
      character(len=16) :: grp
      character(len=*), parameter :: nl = achar(10)
      integer :: pos, nbytes

      h5 = basename(h5_path)
      ntypes = count(ncells > 0)
      kind_used = 0
      do k = 1, 4
         if (ncells(k) > 0) kind_used = k
      end do
      ! write to a temporary file, then rename: a reader never sees half a file
      tmp = path//'.tmp'
      open (newunit=u, file=tmp, status='replace', action='write', access='stream', form='formatted', &
            iostat=ierr)
      if (ierr /= 0) return
      write (u, '(a)', iostat=ierr) '<?xml version="1.0" ?>'//nl// &
         '<!DOCTYPE Xdmf SYSTEM "Xdmf.dtd" []>'//nl// &
         '<Xdmf Version="2.0" xmlns:xi="http://www.w3.org/2001/XInclude">'//nl// &
         '  <Domain>'//nl// &
         '    <Grid Name="Kontakt2D" GridType="Collection" CollectionType="Temporal">'
      do i = 1, size(incs)
         write (grp, '(i5.5)') incs(i)
         write (u, '(a)', iostat=ierr) '      <Grid Name="increment '//trim(grp)//'" GridType="Uniform">'//nl// &
            '        <Time Value="'//itoa(incs(i))//'" />'//nl// &
            '        <Information Name="load_factor" Value="'//factors(lambda(:, i))//'" />'
         if (ntypes == 1) then
            write (u, '(a)', iostat=ierr) '        <Topology TopologyType="'//trim(XDMF_TYPE(kind_used))// &
               '" NumberOfElements="'//itoa(ncells(kind_used))//'">'//nl// &
               '          <DataItem Dimensions="'//itoa(ncells(kind_used))//' '//itoa(CELL_NNODE(kind_used))// &
               '" NumberType="Int" Precision="4" Format="HDF">'//h5//':/mesh/cells_'// &
               trim(CELL_NAMES(kind_used))//'</DataItem>'//nl//'        </Topology>'
         else
            write (u, '(a)', iostat=ierr) '        <Topology TopologyType="Mixed" NumberOfElements="'// &
               itoa(sum(ncells))//'">'//nl// &
               '          <DataItem Dimensions="'//itoa(nmixed)//'" NumberType="Int" Precision="4" '// &
               'Format="HDF">'//h5//':/mesh/cells_mixed</DataItem>'//nl//'        </Topology>'
         end if
         write (u, '(a)', iostat=ierr) '        <Geometry GeometryType="XY">'//nl// &
            '          <DataItem Dimensions="'//itoa(npoin)//' 2" NumberType="Float" Precision="8" '// &
            'Format="HDF">'//h5//':/mesh/coordinates</DataItem>'//nl//'        </Geometry>'//nl// &
            '        <Attribute Name="displacement" AttributeType="Vector" Center="Node">'//nl// &
            '          <DataItem Dimensions="'//itoa(npoin)//' 2" NumberType="Float" Precision="8" '// &
            'Format="HDF">'//h5//':/increments/'//trim(grp)//'/displacement</DataItem>'//nl// &
            '        </Attribute>'
         do k = 1, 4
            write (u, '(a)', iostat=ierr) stress_attribute(k, grp)
         end do
         write (u, '(a)', iostat=ierr) '      </Grid>'
      end do
      write (u, '(a)', iostat=ierr) '    </Grid>'//nl//'  </Domain>'//nl//'</Xdmf>'
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
         open (newunit=u, file=tmp, status='old', iostat=k)
         if (k == 0) close (u, status='delete')
         return
      end if
      call rename_file(tmp, path, ierr)
   contains
      !> One nodal stress component as a hyperslab (column k-1) of stress_nodal.
      function stress_attribute(k, grp) result(s)
         integer, intent(in) :: k
         character(len=*), intent(in) :: grp
         character(len=:), allocatable :: s
         character(len=2), parameter :: comp(4) = ['xx', 'yy', 'xy', 'zz']
         s = '        <Attribute Name="stress_'//comp(k)//'" AttributeType="Scalar" Center="Node">'//nl// &
             '          <DataItem ItemType="HyperSlab" Dimensions="'//itoa(npoin)//' 1">'//nl// &
             '            <DataItem Dimensions="3 2" Format="XML">0 '//itoa(k - 1)//' 1 1 '//itoa(npoin)// &
             ' 1</DataItem>'//nl// &
             '            <DataItem Dimensions="'//itoa(npoin)//' 4" NumberType="Float" Precision="8" '// &
             'Format="HDF">'//h5//':/increments/'//trim(grp)//'/stress_nodal</DataItem>'//nl// &
             '          </DataItem>'//nl//'        </Attribute>'
      end function stress_attribute
   end subroutine write_xdmf

   !> Load factors as "l1 l2 ...".
   function factors(l) result(s)
      real(dp), intent(in) :: l(:)
      character(len=:), allocatable :: s
      character(len=32) :: b
      integer :: k
      s = ''
      do k = 1, size(l)
         write (b, '(es16.8)') l(k)
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
