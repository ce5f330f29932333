!> Degree-of-freedom map: restraint codes to equation numbers.
!!
!! `id(idof, ipoin)` > 0 is the equation of a free dof, < 0 is minus the index
!! of a restrained dof (fixed or prescribed).  Free dofs are numbered in the
!! node order given by `order` (identity, or a bandwidth-reducing permutation),
!! so renumbering never changes the user's node numbers.  Several dofs may
!! share one equation (ties).
!!
!! Ref: Hinton & Owen (1977), the restraint codes IFPRE/NOFIX and equation numbering.
module dof_map
   use model, only: model_t
   use strings, only: itoa
   implicit none
   private
   public :: dof_map_t, build_dof_map

   type :: dof_map_t
      integer :: npoin = 0
      integer :: neq = 0                 !! free equations
      integer :: nres = 0                !! restrained dofs
      integer, allocatable :: id(:, :)   !! (2, npoin)
      integer, allocatable :: res_node(:), res_dof(:)  !! (nres) node and dof of each restrained dof
      integer, allocatable :: eq_node(:), eq_dof(:)    !! (neq) first node and dof of each equation
   contains
      procedure :: describe => describe_equation
   end type dof_map_t

contains

   !> Number the equations.
   subroutine build_dof_map(m, order, map, ties)
      type(model_t), intent(in) :: m
      integer, intent(in) :: order(:)       !! (npoin) nodes in numbering order
      type(dof_map_t), intent(out) :: map
      integer, intent(in), optional :: ties(:, :)  !! (3, ntie): master node, slave node, dof (1, 2)
      logical, allocatable :: fixed(:, :)
      integer :: k, ip, idof, ieq, ires, kt, master, slave

      map%npoin = m%npoin
      allocate (map%id(2, m%npoin), fixed(2, m%npoin))
      fixed = .false.
      do k = 1, size(m%fixes)
         fixed(:, m%fixes(k)%node) = fixed(:, m%fixes(k)%node) .or. m%fixes(k)%fixed
      end do
      map%id = 0
      ires = 0
      ieq = 0
      do k = 1, m%npoin
         ip = order(k)
         do idof = 1, 2
            if (fixed(idof, ip)) then
               ires = ires + 1
               map%id(idof, ip) = -ires
            end if
         end do
      end do
      ! tied slaves take their master's number (masters are numbered first)
      do k = 1, m%npoin
         ip = order(k)
         do idof = 1, 2
            if (map%id(idof, ip) /= 0) cycle
            if (present(ties)) then
               if (is_slave(ip, idof)) cycle
            end if
            ieq = ieq + 1
            map%id(idof, ip) = ieq
         end do
      end do
      if (present(ties)) then
         do kt = 1, size(ties, 2)
            master = ties(1, kt)
            slave = ties(2, kt)
            idof = ties(3, kt)
            map%id(idof, slave) = map%id(idof, master)
         end do
      end if
      map%neq = ieq
      map%nres = ires
      allocate (map%res_node(ires), map%res_dof(ires), map%eq_node(ieq), map%eq_dof(ieq))
      map%eq_node = 0
      do ip = 1, m%npoin
         do idof = 1, 2
            if (map%id(idof, ip) < 0) then
               map%res_node(-map%id(idof, ip)) = ip
               map%res_dof(-map%id(idof, ip)) = idof
            else if (map%id(idof, ip) > 0) then
               if (map%eq_node(map%id(idof, ip)) == 0) then
                  map%eq_node(map%id(idof, ip)) = ip
                  map%eq_dof(map%id(idof, ip)) = idof
               end if
            end if
         end do
      end do
   contains
      logical function is_slave(node, dof)
         integer, intent(in) :: node, dof
         integer :: j
         is_slave = .false.
         do j = 1, size(ties, 2)
            if (ties(2, j) == node .and. ties(3, j) == dof) then
               is_slave = .true.
               return
            end if
         end do
      end function is_slave
   end subroutine build_dof_map

   !> "node N, dof x" for an equation number, for messages.
   function describe_equation(this, ieq) result(s)
      class(dof_map_t), intent(in) :: this
      integer, intent(in) :: ieq
      character(len=:), allocatable :: s
      character(len=1), parameter :: dofname(2) = ['x', 'y']
      if (ieq < 1 .or. ieq > this%neq) then
         s = 'equation '//itoa(ieq)
      else
         s = 'node '//itoa(this%eq_node(ieq))//', dof '//dofname(this%eq_dof(ieq))// &
             ' (equation '//itoa(ieq)//')'
      end if
   end function describe_equation
end module dof_map
