!> Anisotropy of the rigid surface and of the deformed solid (section 3 of the paper), and the
!> statistics of contact patches.
!>
!> Slope tensors in a band of wavevectors: M_ij = <d_i h d_j h>, Md_ij = <d_i w d_j w> (second
!> spectral moments of the band-filtered fields). m2(theta) = e.M.e, gamma = lambda_min/lambda_max,
!> theta = direction of lambda_max in [0, pi). The paper's eq. (16), Md = R_phi Sigma_d M R_phi^T
!> with Sigma_d = R_theta_s diag(sigma1, sigma2) R_theta_s^T, says: Md has the eigenvectors of M
!> turned by phi, and eigenvalues sigma1 m_1 and sigma2 m_2. Matching rule (stated, tested):
!>   - the eigenpairs of Md and M are paired so that |phi| is smallest (phi in (-pi/2, pi/2]);
!>     sigma1 belongs to the major axis of M, sigma2 to its minor axis;
!>   - when M is isotropic within `iso_tol` (1 - gamma_s <= iso_tol) its axes are undefined: the
!>     rule takes theta_s = theta_d, so phi = 0, sigma1 = lambda_max(Md)/m, sigma2 = lambda_min(Md)/m;
!>   - when Md is isotropic within iso_tol, phi = 0 likewise.
module veslide_anisotropy
    use veslide_kinds, only: dp, pi
    implicit none
    private
    public :: tensor_axes, decompose, compose, m2_of_theta, patch_stats_t, contact_patches, percolates

    type :: patch_stats_t
        integer :: count = 0                    !! number of patches
        real(dp) :: mean_area_fraction = 0.0_dp !! mean patch area / cell area
        real(dp) :: orientation(2, 2) = 0.0_dp  !! area-weighted gyration tensor, trace 1
        real(dp) :: gamma = 0.0_dp              !! its eigenvalue ratio (min/max)
        real(dp) :: theta = 0.0_dp              !! direction of its major axis [rad, 0..pi)
    end type patch_stats_t

contains

    !> Eigenvalues (l1 >= l2) of a symmetric 2x2 tensor, the direction theta in [0, pi) of l1
    pure subroutine tensor_axes(m, l1, l2, theta)
        real(dp), intent(in) :: m(2, 2)
        real(dp), intent(out) :: l1, l2, theta
        real(dp) :: tr, dif
        tr = m(1, 1) + m(2, 2)
        dif = sqrt((m(1, 1) - m(2, 2))**2 + 4.0_dp*m(1, 2)**2)
        l1 = 0.5_dp*(tr + dif); l2 = 0.5_dp*(tr - dif)
        theta = modulo(0.5_dp*atan2(2.0_dp*m(1, 2), m(1, 1) - m(2, 2)), pi)
        if (theta > pi*(1.0_dp - 1.0e-12_dp)) theta = 0.0_dp   ! -0 from atan2 is the axis 0, not pi
    end subroutine tensor_axes

    !> m2(theta) = e(theta).M.e(theta) at the given angles
    pure function m2_of_theta(m, theta) result(m2)
        real(dp), intent(in) :: m(2, 2), theta(:)
        real(dp) :: m2(size(theta))
        m2 = m(1, 1)*cos(theta)**2 + 2.0_dp*m(1, 2)*sin(theta)*cos(theta) + m(2, 2)*sin(theta)**2
    end function m2_of_theta

    pure real(dp) function wrap_half_pi(a) result(w)
        real(dp), intent(in) :: a
        w = modulo(a + 0.5_dp*pi, pi) - 0.5_dp*pi
        if (w <= -0.5_dp*pi) w = w + pi
    end function wrap_half_pi

    !> sigma1, sigma2, phi of eq. (16) from M (rigid) and Md (deformed); see the module's rule
    pure subroutine decompose(m, md, iso_tol, sigma1, sigma2, phi)
        real(dp), intent(in) :: m(2, 2), md(2, 2), iso_tol
        real(dp), intent(out) :: sigma1, sigma2, phi
        real(dp) :: l1, l2, ts, d1, d2, td, phi_same, phi_swap
        call tensor_axes(m, l1, l2, ts)
        call tensor_axes(md, d1, d2, td)
        if (1.0_dp - l2/l1 <= iso_tol .or. 1.0_dp - d2/d1 <= iso_tol) then
            phi = 0.0_dp
            if (1.0_dp - l2/l1 <= iso_tol) then
                sigma1 = d1/(0.5_dp*(l1 + l2)); sigma2 = d2/(0.5_dp*(l1 + l2))
            else
                sigma1 = 0.5_dp*(d1 + d2)/l1; sigma2 = 0.5_dp*(d1 + d2)/l2
            end if
            return
        end if
        phi_same = wrap_half_pi(td - ts)            ! major of Md <- major of M
        phi_swap = wrap_half_pi(td - ts - 0.5_dp*pi) ! major of Md <- minor of M
        if (abs(phi_same) <= abs(phi_swap)) then
            phi = phi_same; sigma1 = d1/l1; sigma2 = d2/l2
        else
            phi = phi_swap; sigma1 = d2/l1; sigma2 = d1/l2
        end if
    end subroutine decompose

    !> Md = R_phi Sigma_d M R_phi^T, Sigma_d = R_theta_s diag(sigma1, sigma2) R_theta_s^T
    pure function compose(m, sigma1, sigma2, phi) result(md)
        real(dp), intent(in) :: m(2, 2), sigma1, sigma2, phi
        real(dp) :: md(2, 2), l1, l2, ts, r(2, 2), rs(2, 2), sd(2, 2)
        call tensor_axes(m, l1, l2, ts)
        rs = reshape([cos(ts), sin(ts), -sin(ts), cos(ts)], [2, 2])
        r = reshape([cos(phi), sin(phi), -sin(phi), cos(phi)], [2, 2])
        sd = matmul(rs, matmul(reshape([sigma1, 0.0_dp, 0.0_dp, sigma2], [2, 2]), transpose(rs)))
        md = matmul(r, matmul(matmul(sd, m), transpose(r)))
    end function compose

    !> Neighbour k (1..4: +x, -x, +y, -y) of cell (ci, cj) on the periodic grid, and the unwrapped
    !> cell offsets (ox, oy) carried across the boundary
    pure subroutine periodic_step(ci, cj, k, nx, ny, ox, oy, ni, nj, dx, dy)
        integer, intent(in) :: ci, cj, k, nx, ny, ox, oy
        integer, intent(out) :: ni, nj, dx, dy
        integer, parameter :: di(4) = [1, -1, 0, 0], dj(4) = [0, 0, 1, -1]
        ni = ci + di(k); nj = cj + dj(k); dx = ox; dy = oy
        if (ni < 1) then
            ni = nx; dx = dx - 1
        else if (ni > nx) then
            ni = 1; dx = dx + 1
        end if
        if (nj < 1) then
            nj = ny; dy = dy - 1
        else if (nj > ny) then
            nj = 1; dy = dy + 1
        end if
    end subroutine periodic_step

    !> Connected patches of `mask` (4-neighbour, periodic): labels, and their statistics
    subroutine contact_patches(mask, lx, ly, stats, labels)
        logical, intent(in) :: mask(:, :)
        real(dp), intent(in) :: lx, ly
        type(patch_stats_t), intent(out) :: stats
        integer, allocatable, intent(out), optional :: labels(:, :)
        integer, allocatable :: lab(:, :), qi(:), qj(:), ox(:, :), oy(:, :)
        integer :: nx, ny, i, j, head, tail, ci, cj, k, ni, nj, dx, dy, npatch, cnt
        real(dp) :: sx, sy, sxx, syy, sxy, x, y, g(2, 2), a, l1, l2, wsum
        nx = size(mask, 1); ny = size(mask, 2)
        allocate (lab(nx, ny), qi(nx*ny), qj(nx*ny), ox(nx, ny), oy(nx, ny))
        lab = 0; ox = 0; oy = 0; npatch = 0
        stats%orientation = 0.0_dp; wsum = 0.0_dp
        do j = 1, ny
            do i = 1, nx
                if (.not. mask(i, j) .or. lab(i, j) /= 0) cycle
                npatch = npatch + 1
                lab(i, j) = npatch; ox(i, j) = 0; oy(i, j) = 0
                head = 1; tail = 1; qi(1) = i; qj(1) = j
                cnt = 0; sx = 0; sy = 0; sxx = 0; syy = 0; sxy = 0
                do while (head <= tail)
                    ci = qi(head); cj = qj(head); head = head + 1
                    ! unwrapped position of this cell in units of cells
                    x = real(ci - 1 + ox(ci, cj)*nx, dp)*lx/nx
                    y = real(cj - 1 + oy(ci, cj)*ny, dp)*ly/ny
                    cnt = cnt + 1; sx = sx + x; sy = sy + y; sxx = sxx + x*x; syy = syy + y*y; sxy = sxy + x*y
                    do k = 1, 4
                        call periodic_step(ci, cj, k, nx, ny, ox(ci, cj), oy(ci, cj), ni, nj, dx, dy)
                        if (.not. mask(ni, nj) .or. lab(ni, nj) /= 0) cycle
                        lab(ni, nj) = npatch; ox(ni, nj) = dx; oy(ni, nj) = dy
                        tail = tail + 1; qi(tail) = ni; qj(tail) = nj
                    end do
                end do
                a = real(cnt, dp)
                g(1, 1) = sxx/a - (sx/a)**2 + (lx/nx)**2/12.0_dp
                g(2, 2) = syy/a - (sy/a)**2 + (ly/ny)**2/12.0_dp
                g(1, 2) = sxy/a - (sx/a)*(sy/a); g(2, 1) = g(1, 2)
                stats%orientation = stats%orientation + a*g
                wsum = wsum + a*(g(1, 1) + g(2, 2))
            end do
        end do
        stats%count = npatch
        if (npatch > 0) then
            stats%mean_area_fraction = real(count(mask), dp)/npatch/(real(nx, dp)*ny)
            stats%orientation = stats%orientation/wsum
            call tensor_axes(stats%orientation, l1, l2, stats%theta)
            stats%gamma = l2/l1
        end if
        if (present(labels)) call move_alloc(lab, labels)
    end subroutine contact_patches

    !> Does some connected component of `mask` wrap around the periodic cell along x (dir = 1)
    !> or along y (dir = 2)? A component wraps when a cell is reached with two unwrapped offsets.
    logical function percolates(mask, dir) result(yes)
        logical, intent(in) :: mask(:, :)
        integer, intent(in) :: dir
        integer, allocatable :: lab(:, :), qi(:), qj(:), ox(:, :), oy(:, :)
        integer :: nx, ny, i, j, head, tail, ci, cj, k, ni, nj, dx, dy, ncomp
        nx = size(mask, 1); ny = size(mask, 2)
        allocate (lab(nx, ny), qi(nx*ny), qj(nx*ny), ox(nx, ny), oy(nx, ny))
        lab = 0; ox = 0; oy = 0; ncomp = 0; yes = .false.
        do j = 1, ny
            do i = 1, nx
                if (.not. mask(i, j) .or. lab(i, j) /= 0) cycle
                ncomp = ncomp + 1
                lab(i, j) = ncomp
                head = 1; tail = 1; qi(1) = i; qj(1) = j
                do while (head <= tail)
                    ci = qi(head); cj = qj(head); head = head + 1
                    do k = 1, 4
                        call periodic_step(ci, cj, k, nx, ny, ox(ci, cj), oy(ci, cj), ni, nj, dx, dy)
                        if (.not. mask(ni, nj)) cycle
                        if (lab(ni, nj) /= 0) then
                            if ((dir == 1 .and. dx /= ox(ni, nj)) .or. (dir == 2 .and. dy /= oy(ni, nj))) then
                                yes = .true.; return
                            end if
                            cycle
                        end if
                        lab(ni, nj) = ncomp; ox(ni, nj) = dx; oy(ni, nj) = dy
                        tail = tail + 1; qi(tail) = ni; qj(tail) = nj
                    end do
                end do
            end do
        end do
    end function percolates

end module veslide_anisotropy
