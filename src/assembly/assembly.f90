!> Assembly of the bodies' stiffness K_AB and of the load vectors.
!!
!! K_AB is assembled once into the solver (the bodies are linear elastic,
!! small strain: the paper's eq. 4.12).  Entries that couple to a restrained
!! dof are kept aside in a `coupling_t` list: the free-row part moves
!! prescribed displacements to the right-hand side, the restrained-row part
!! gives the reactions, without a second pass over the elements.
!!
!! Global dof index g = 2*(ipoin - 1) + idof is used for nodal vectors.
module assembly
   use kinds, only: dp
   use errors, only: status_t, STAT_JACOBIAN
   use strings, only: itoa
   use model, only: model_t, MAX_NODE
   use dof_map, only: dof_map_t
   use linear_solver, only: linear_solver_t
   use solid2d, only: element_stiffness, edge_load, body_load, solid_bad_element, solid_bad_radius
   implicit none
   private
   public :: coupling_t, assemble_bodies, assemble_load_cases, element_equations, &
             subtract_prescribed, restrained_forces, element_error, load_increment

   !> Stiffness entries with a restrained row or column (COO).
   type :: coupling_t
      integer :: n = 0
      integer, allocatable :: row(:), col(:)   !! global dof indices
      real(dp), allocatable :: val(:)
   end type coupling_t

contains

   !> Equation numbers and global dof indices of the dofs of element ie.
   pure subroutine element_equations(m, map, ie, ieq, gdof, nevab)
      type(model_t), intent(in) :: m
      type(dof_map_t), intent(in) :: map
      integer, intent(in) :: ie
      integer, intent(out) :: ieq(2*MAX_NODE), gdof(2*MAX_NODE)
      integer, intent(out) :: nevab
      integer :: k, ip
      nevab = 2*m%nnode_e(ie)
      ieq = 0
      gdof = 0
      do k = 1, m%nnode_e(ie)
         ip = m%lnods(k, ie)
         ieq(2*k - 1:2*k) = map%id(:, ip)
         gdof(2*k - 1) = 2*(ip - 1) + 1
         gdof(2*k) = 2*(ip - 1) + 2
      end do
   end subroutine element_equations

   !> Text for an element routine's error code.
   pure function element_error(ierr) result(s)
      integer, intent(in) :: ierr
      character(len=:), allocatable :: s
      select case (ierr)
      case (solid_bad_element)
         s = 'unsupported element, analysis type or Gauss rule'
      case (solid_bad_radius)
         s = 'a Gauss point lies at radius r <= 0 in an axisymmetric analysis'
      case default
         s = 'non-positive Jacobian determinant at Gauss point '//itoa(ierr)// &
               ' (distorted or inverted element)'
      end select
   end function element_error

   !> Add every element's stiffness to the solver; keep restrained couplings;
   !! optionally the diagonal of K_AB on the free equations (the stiffness
   !! scale of the bodies at each equation).
   subroutine assemble_bodies(m, map, solver, coup, status, diag, absrow)
      type(model_t), intent(in) :: m
      type(dof_map_t), intent(in) :: map
      class(linear_solver_t), intent(inout) :: solver
      type(coupling_t), intent(out) :: coup
      type(status_t), intent(inout) :: status
      real(dp), intent(out), optional :: diag(:)   !! (neq) diagonal of K_AB
      real(dp), intent(out), optional :: absrow(:) !! (neq) sum of |k_ij| over the
                                                   !! elements and j (roundoff)
      real(dp) :: estif(2*MAX_NODE, 2*MAX_NODE), elcod(2, MAX_NODE)
      integer :: ieq(2*MAX_NODE), gdof(2*MAX_NODE), ie, nn, nevab, ierr, i, j
      integer :: imat

      allocate (coup%row(1024), coup%col(1024), coup%val(1024))
      coup%n = 0
      if (present(diag)) diag = 0.0_dp
      if (present(absrow)) absrow = 0.0_dp
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
         call element_stiffness(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, &
                                m%mats(imat)%poiss, &
                                m%mats(imat)%thick, m%ngaus, estif(1:2*nn, 1:2*nn), ierr)
         if (ierr /= 0) then
            call status%set(STAT_JACOBIAN, 'element '//itoa(ie)//': '//element_error(ierr))
            return
         end if
         call element_equations(m, map, ie, ieq, gdof, nevab)
         call solver%add_element(ieq(1:nevab), estif(1:nevab, 1:nevab))
         if (present(diag)) then
            do i = 1, nevab
               if (ieq(i) > 0) diag(ieq(i)) = diag(ieq(i)) + estif(i, i)
            end do
         end if
         if (present(absrow)) then
            do i = 1, nevab
               if (ieq(i) > 0) absrow(ieq(i)) = absrow(ieq(i)) + sum(abs(estif(i, 1:nevab)))
            end do
         end if
         do j = 1, nevab
            do i = 1, nevab
               if (ieq(i) < 0 .or. ieq(j) < 0) then
                  if (abs(estif(i, j)) > 0.0_dp) call push(gdof(i), gdof(j), estif(i, j))
               end if
            end do
         end do
      end do
   contains
      subroutine push(r, c, v)
         integer, intent(in) :: r, c
         real(dp), intent(in) :: v
         integer, allocatable :: ti(:)
         real(dp), allocatable :: tv(:)
         if (coup%n >= size(coup%row)) then
            allocate (ti(2*size(coup%row)))
            ti(1:coup%n) = coup%row(1:coup%n)
            call move_alloc(ti, coup%row)
            allocate (ti(2*size(coup%col)))
            ti(1:coup%n) = coup%col(1:coup%n)
            call move_alloc(ti, coup%col)
            allocate (tv(2*size(coup%val)))
            tv(1:coup%n) = coup%val(1:coup%n)
            call move_alloc(tv, coup%val)
         end if
         coup%n = coup%n + 1
         coup%row(coup%n) = r
         coup%col(coup%n) = c
         coup%val(coup%n) = v
      end subroutine push
   end subroutine assemble_bodies

   !> Nodal force vectors and prescribed displacements of each load case at factor 1.
   subroutine assemble_load_cases(m, fcase, ucase, status)
      type(model_t), intent(in) :: m
      real(dp), allocatable, intent(out) :: fcase(:, :, :)  !! (2, npoin, ncase) external forces
      real(dp), allocatable, intent(out) :: ucase(:, :, :)  !! (2, npoin, ncase) prescribed
                                                            !! displacements
      type(status_t), intent(inout) :: status
      real(dp) :: eforce(2*MAX_NODE), elcod(2, MAX_NODE), edcod(2, 3)
      integer :: k, ie, nn, ierr, imat, ic, ip, j

      allocate (fcase(2, m%npoin, m%ncase), ucase(2, m%npoin, m%ncase))
      fcase = 0.0_dp
      ucase = 0.0_dp
      do k = 1, size(m%point_loads)
         associate (p => m%point_loads(k))
            fcase(:, p%node, p%icase) = fcase(:, p%node, p%icase) + p%force
         end associate
      end do
      do k = 1, size(m%edge_loads)
         associate (e => m%edge_loads(k))
            ie = e%ielem
            imat = m%matno(ie)
            edcod(:, 1:e%nn) = m%coord(:, e%nodes(1:e%nn))
            call edge_load(m%ntype, e%nn, edcod(:, 1:e%nn), e%pn(1:e%nn), e%pt(1:e%nn), &
                           m%mats(imat)%thick, eforce(1:2*e%nn))
            do j = 1, e%nn
               ip = e%nodes(j)
               fcase(:, ip, e%icase) = fcase(:, ip, e%icase) + eforce(2*j - 1:2*j)
            end do
         end associate
      end do
      do k = 1, size(m%body_loads)
         associate (b => m%body_loads(k))
            do ie = 1, m%nelem
               imat = m%matno(ie)
               if (b%imat /= 0 .and. b%imat /= imat) cycle
               nn = m%nnode_e(ie)
               elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
               call body_load(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%thick, b%b(1), b%b(2), &
                              m%ngaus, &
                              eforce(1:2*nn), ierr)
               if (ierr /= 0) then
                  call status%set(STAT_JACOBIAN, 'element '//itoa(ie)//': '//element_error(ierr))
                  return
               end if
               do j = 1, nn
                  ip = m%lnods(j, ie)
                  fcase(:, ip, b%icase) = fcase(:, ip, b%icase) + eforce(2*j - 1:2*j)
               end do
            end do
         end associate
      end do
      do k = 1, size(m%fixes)
         associate (f => m%fixes(k))
            ic = f%icase
            where (f%fixed) ucase(:, f%node, ic) = f%value
         end associate
      end do
   end subroutine assemble_load_cases

   !> Right-hand side and prescribed displacements of a load increment dlam:
   !! rhs = carry + the forces of the load cases, minus K_fr du_r for the
   !! prescribed displacement increments du_r, which go to du.
   subroutine load_increment(coup, map, fcase, ucase, restrained, dlam, carry, rhs, du)
      type(coupling_t), intent(in) :: coup
      type(dof_map_t), intent(in) :: map
      real(dp), intent(in) :: fcase(:, :, :)  !! (2, npoin, ncase) external forces at factor 1
      real(dp), intent(in) :: ucase(:, :, :)  !! (2, npoin, ncase) prescribed
                                              !! displacements at factor 1
      logical, intent(in) :: restrained(:, :) !! (2, npoin)
      real(dp), intent(in) :: dlam(:)         !! (ncase) increments of the load factors
      real(dp), intent(in) :: carry(:)        !! (neq) out-of-balance force carried
                                              !! from the last increment
      real(dp), intent(out) :: rhs(:)         !! (neq)
      real(dp), intent(inout) :: du(:, :)     !! (2, npoin) zero in, prescribed increments out
      integer :: ic, ip, idof
      rhs = carry
      do ic = 1, size(dlam)
         where (restrained) du = du + dlam(ic)*ucase(:, :, ic)
      end do
      do ip = 1, size(du, 2)
         do idof = 1, 2
            if (map%id(idof, ip) > 0) then
               rhs(map%id(idof, ip)) = rhs(map%id(idof, ip)) + sum(dlam*fcase(idof, ip, :))
            end if
         end do
      end do
      call subtract_prescribed(coup, map, du, rhs)
   end subroutine load_increment

   !> rhs(free) -= K_fr u_r: move prescribed displacements to the right-hand side.
   pure subroutine subtract_prescribed(coup, map, u, rhs)
      type(coupling_t), intent(in) :: coup
      type(dof_map_t), intent(in) :: map
      real(dp), intent(in) :: u(:, :)        !! (2, npoin) displacements,
                                             !! only restrained entries used
      real(dp), intent(inout) :: rhs(:)      !! (neq)
      integer :: k, ieq, jres
      do k = 1, coup%n
         ieq = map%id(mod(coup%row(k) - 1, 2) + 1, (coup%row(k) - 1)/2 + 1)
         if (ieq <= 0) cycle
         jres = map%id(mod(coup%col(k) - 1, 2) + 1, (coup%col(k) - 1)/2 + 1)
         if (jres >= 0) cycle
         rhs(ieq) = rhs(ieq) - coup%val(k)*u(mod(coup%col(k) - 1, 2) + 1, (coup%col(k) - 1)/2 + 1)
      end do
   end subroutine subtract_prescribed

   !> Internal forces K u at the restrained dofs (zero elsewhere).
   pure subroutine restrained_forces(coup, map, u, fr)
      type(coupling_t), intent(in) :: coup
      type(dof_map_t), intent(in) :: map
      real(dp), intent(in) :: u(:, :)        !! (2, npoin)
      real(dp), intent(out) :: fr(:, :)      !! (2, npoin)
      integer :: k, irow, icol
      fr = 0.0_dp
      do k = 1, coup%n
         irow = coup%row(k)
         if (map%id(mod(irow - 1, 2) + 1, (irow - 1)/2 + 1) >= 0) cycle
         icol = coup%col(k)
         fr(mod(irow - 1, 2) + 1, (irow - 1)/2 + 1) = fr(mod(irow - 1, 2) + 1, (irow - 1)/2 + 1) + &
                                                     coup%val(k)*u(mod(icol - 1, 2) + 1, &
                                                                   (icol - 1)/2 + 1)
      end do
   end subroutine restrained_forces
end module assembly
