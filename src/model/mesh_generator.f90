!> Structured meshes of rectangular blocks, for tests, benchmarks and the
!! deck-writing tools: T3, Q4, Q8 or Q9 elements on an (nx x ny) grid with
!! optional geometric grading.  Node numbering runs row by row from the
!! lower-left corner over the (2nx+1) x (2ny+1) grid of a quadratic mesh or
!! the (nx+1) x (ny+1) grid of a linear one.
module mesh_generator
   use kinds, only: dp
   use model, only: model_t, MAX_NODE
   implicit none
   private
   public :: generate_block, grid_coordinate

contains

   !> Coordinate of grid line k of n cells on [a, b] with ratio `grade`
   !! between the last and the first cell (1 = uniform).
   pure real(dp) function grid_coordinate(k, n, a, b, grade) result(x)
      integer, intent(in) :: k, n      !! 0 <= k <= n (k may be a half step: see generate_block)
      real(dp), intent(in) :: a, b, grade
      real(dp) :: q, s
      if (abs(grade - 1.0_dp) < 1.0e-12_dp .or. n <= 1) then
         x = a + (b - a)*real(k, dp)/real(n, dp)
      else
         q = grade**(1.0_dp/real(n - 1, dp))
         s = (q**k - 1.0_dp)/(q**n - 1.0_dp)
         x = a + (b - a)*s
      end if
   end function grid_coordinate

   !> Fill the mesh part of `m` (npoin, coord, nelem, lnods, nnode_e, matno).
   !! Quadratic nodes sit at the parameter mid-points of the graded lines.
   subroutine generate_block(m, nnode, nx, ny, x0, x1, y0, y1, grade_x, grade_y)
      type(model_t), intent(inout) :: m
      integer, intent(in) :: nnode          !! 3, 4, 8 or 9
      integer, intent(in) :: nx, ny         !! cells in x and y
      real(dp), intent(in) :: x0, x1, y0, y1
      real(dp), intent(in), optional :: grade_x, grade_y   !! last/first cell size ratio
      real(dp) :: gx, gy
      real(dp), allocatable :: xs(:), ys(:)
      integer :: ngx, ngy, step, i, j, ie, n00, n10, n11, n01

      gx = 1.0_dp
      gy = 1.0_dp
      if (present(grade_x)) gx = grade_x
      if (present(grade_y)) gy = grade_y
      step = merge(2, 1, nnode >= 8)
      ngx = step*nx + 1
      ngy = step*ny + 1
      allocate (xs(ngx), ys(ngy))
      do i = 0, nx
         xs(step*i + 1) = grid_coordinate(i, nx, x0, x1, gx)
      end do
      do j = 0, ny
         ys(step*j + 1) = grid_coordinate(j, ny, y0, y1, gy)
      end do
      if (step == 2) then
         do i = 1, nx
            xs(2*i) = 0.5_dp*(xs(2*i - 1) + xs(2*i + 1))
         end do
         do j = 1, ny
            ys(2*j) = 0.5_dp*(ys(2*j - 1) + ys(2*j + 1))
         end do
      end if

      m%nnode = nnode
      m%npoin = ngx*ngy
      if (nnode == 8) m%npoin = ngx*ngy - nx*ny   ! no centre nodes
      m%nelem = nx*ny
      if (nnode == 3) m%nelem = 2*nx*ny
      if (allocated(m%coord)) deallocate (m%coord)
      if (allocated(m%lnods)) deallocate (m%lnods)
      if (allocated(m%nnode_e)) deallocate (m%nnode_e)
      if (allocated(m%matno)) deallocate (m%matno)
      if (allocated(m%node_line)) deallocate (m%node_line)
      if (allocated(m%elem_line)) deallocate (m%elem_line)
      allocate (m%coord(2, m%npoin), m%lnods(MAX_NODE, m%nelem), m%nnode_e(m%nelem), &
                m%matno(m%nelem), &
                m%node_line(m%npoin), m%elem_line(m%nelem))
      m%lnods = 0
      m%nnode_e = nnode
      m%matno = 1
      m%node_line = 0
      m%elem_line = 0
      do j = 1, ngy
         do i = 1, ngx
            if (node_id(i, j) > 0) m%coord(:, node_id(i, j)) = [xs(i), ys(j)]
         end do
      end do
      ie = 0
      do j = 1, ny
         do i = 1, nx
            n00 = node_id(step*(i - 1) + 1, step*(j - 1) + 1)
            n10 = node_id(step*i + 1, step*(j - 1) + 1)
            n11 = node_id(step*i + 1, step*j + 1)
            n01 = node_id(step*(i - 1) + 1, step*j + 1)
            select case (nnode)
            case (3)
               ie = ie + 1
               m%lnods(1:3, ie) = [n00, n10, n11]
               ie = ie + 1
               m%lnods(1:3, ie) = [n00, n11, n01]
            case (4)
               ie = ie + 1
               m%lnods(1:4, ie) = [n00, n10, n11, n01]
            case (8, 9)
               ie = ie + 1
               m%lnods(1:8, ie) = [n00, n10, n11, n01, &
                                   node_id(2*i, 2*j - 1), node_id(2*i + 1, 2*j), &
                                   node_id(2*i, 2*j + 1), node_id(2*i - 1, 2*j)]
               if (nnode == 9) m%lnods(9, ie) = node_id(2*i, 2*j)
            end select
         end do
      end do
   contains
      !> Node number of grid point (i, j); 0 for the missing centre of a Q8 cell.
      pure integer function node_id(i, j)
         integer, intent(in) :: i, j
         integer :: full_rows, rowlen_full, rowlen_mid
         if (nnode /= 8) then
            node_id = (j - 1)*ngx + i
            return
         end if
         ! Q8: rows with odd j have ngx nodes, rows with even j only nx + 1
         rowlen_full = ngx
         rowlen_mid = nx + 1
         full_rows = j/2      ! complete (full + mid) row pairs before row j
         if (mod(j, 2) == 1) then
            node_id = full_rows*(rowlen_full + rowlen_mid) + i
         else
            if (mod(i, 2) == 0) then
               node_id = 0
            else
               node_id = (full_rows - 1)*(rowlen_full + rowlen_mid) + rowlen_full + (i + 1)/2
            end if
         end if
      end function node_id
   end subroutine generate_block
end module mesh_generator
