!> Anisotropy of the rigid surface and of the deformed solid (section 3 of the paper); the
!> statistics of contact patches are in veslide_patches.
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
    public :: tensor_axes, decompose, compose, m2_of_theta

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

end module veslide_anisotropy
