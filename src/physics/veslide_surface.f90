!> Rigid surfaces: the elliptical self-affine random surface of appendix B, deterministic
!> validation scenes, and slope/height statistics.
!>
!> Heights h(x, y) [m] on an nx x ny periodic grid of cell centres, positive toward the solid
!> (the highest points touch first); each process makes its own rows (nx, ny_local) of a grid. Random surfaces: h(x) = sum_q a_q exp(i q.x) with
!> a_q = alpha + i beta, alpha, beta ~ N(0, (2 pi)^2/(Lx Ly) C(q)/2), a_{-q} = conj(a_q), a_0 = 0,
!> Nyquist lines zero. Each a_q is drawn from (seed, signed wavenumber) alone (veslide_rng), so a
!> finer grid with the same spectrum gives the same surface, sampled more densely.
module veslide_surface
    use veslide_kinds, only: dp, i8, two_pi
    use veslide_error, only: error_t, fatal_error
    use veslide_rng, only: normal_pair_at
    use veslide_grid, only: grid_t
    use veslide_fftw, only: fft2d_t
    use veslide_spectrum, only: slope_tensor
    use veslide_collective, only: ordered_sum
    use veslide_fields, only: field_mean, field_rms
    implicit none
    private
    public :: psd_t, psd_value, random_surface, random_coefficients, rms_height, expected_slope_tensor
    public :: cosine_surface, bisinusoid_surface, paraboloid_surface, cylinder_surface, surface_kind_names

    !> The kinds of rigid surface (the namelist's `&surface kind`); 'file' is a measured topography
    character(len=*), parameter :: surface_kind_names(7) = [character(len=11) :: 'self_affine', 'cosine', &
                                                            'bisinusoid', 'paraboloid', 'cylinder', 'flat', 'file']

    !> Elliptical self-affine power spectral density (appendix B, eq. B.6)
    type :: psd_t
        real(dp) :: hurst = 0.8_dp          !! Hurst exponent H, 0 < H < 1
        real(dp) :: eccentricity = 1.0_dp   !! eps = b/a in (0, 1]; a^2 + b^2 = 2
        real(dp) :: alpha_rad = 0.0_dp      !! angle of the major axis of C(q) from x [rad]
        real(dp) :: q_low = 0.0_dp          !! lower cut-off q_l [1/m]
        real(dp) :: q_roll = 0.0_dp         !! roll-off q_r [1/m] (plateau between q_l and q_r)
        real(dp) :: q_cut = 0.0_dp          !! upper cut-off q_c [1/m]
    end type psd_t

contains

    !> C(q) / C0 of the elliptical self-affine spectrum; zero outside [q_l, q_c]
    elemental real(dp) function psd_value(psd, qx, qy) result(c)
        type(psd_t), intent(in) :: psd
        real(dp), intent(in) :: qx, qy
        real(dp) :: q2, a2, b2, ca, sa, u, v, tqq, s
        q2 = qx*qx + qy*qy
        c = 0.0_dp
        if (q2 < psd%q_low**2*(1.0_dp - 1.0e-12_dp) .or. q2 > psd%q_cut**2*(1.0_dp + 1.0e-12_dp)) return
        a2 = 2.0_dp/(1.0_dp + psd%eccentricity**2)
        b2 = 2.0_dp - a2
        ca = cos(psd%alpha_rad); sa = sin(psd%alpha_rad)
        ! components in the frame of the ellipse: T_alpha q.q = u^2/a^2 + v^2/b^2
        u = ca*qx + sa*qy
        v = -sa*qx + ca*qy
        tqq = u*u/a2 + v*v/b2
        if (q2 <= psd%q_roll**2) then
            s = q2
        else
            s = psd%q_roll**2
        end if
        c = (tqq/s)**(-(psd%hurst + 1.0_dp))
    end function psd_value

    !> Fourier coefficients a_q of a random surface with spectrum `psd` and unit C0 on the r2c
    !> half-spectrum (the grid's spectral storage: (nx/2+1, ny) on one process), so that
    !> h(x) = sum_q a_q exp(i q.x) over the full plane.
    !> Each pair {q, -q} is drawn once, from (seed, signed wavenumber of the representative with
    !> ki > 0, or ki = 0 and kj > 0); the ki = 0 column holds both members, conjugate. The q = 0
    !> mode and Nyquist lines are zero. Any share of the coefficients is drawn independently of the
    !> others. Also returns the expected variance and slope-tensor trace of this process's share,
    !> summed column by column of the storage (`cols`, for an ordered sum over processes).
    subroutine random_coefficients(grid, psd, seed, ak, var_sum, slope_sum, cols)
        type(grid_t), intent(in) :: grid
        type(psd_t), intent(in) :: psd
        integer(i8), intent(in) :: seed
        complex(dp), intent(out) :: ak(:, :)
        !> expected <h^2> and <|grad h|^2> of the spectrum on this grid (this process's share)
        real(dp), intent(out) :: var_sum, slope_sum
        !> the same per storage column, (2, columns)
        real(dp), intent(out), optional :: cols(:, :)
        integer :: a, b, i, j, ki, kj, k(2), ij(2)
        real(dp) :: qx, qy, c, sig, z1, z2, wt, col(2)
        real(dp) :: per_col(2, size(ak, 2))
        logical :: nyq
        ! columns in parallel (each coefficient is drawn from its own counter, and each column's
        ! sums are summed in the column: the same bits on any number of threads)
        !$omp parallel do schedule(dynamic, 16) private(a, i, j, ki, kj, k, ij, qx, qy, c, sig, z1, z2, wt, col, nyq)
        do b = 1, size(ak, 2)
            col = 0.0_dp
            do a = 1, size(ak, 1)
                ij = grid%spectral_index(a, b); i = ij(1); j = ij(2)
                k = grid%wavenumber(i, j); ki = k(1); kj = k(2)
                nyq = grid%is_nyquist_x(i) .or. grid%is_nyquist_y(j)
                qx = two_pi*ki/grid%lx_m; qy = two_pi*kj/grid%ly_m
                c = psd_value(psd, qx, qy)
                if (nyq .or. (ki == 0 .and. kj == 0) .or. c == 0.0_dp) then
                    ak(a, b) = (0.0_dp, 0.0_dp); cycle
                end if
                sig = sqrt(0.5_dp*two_pi**2/(grid%lx_m*grid%ly_m)*c)
                if (ki > 0 .or. kj > 0) then
                    call normal_pair_at(seed, ki, kj, z1, z2)
                    ak(a, b) = sig*cmplx(z1, z2, dp)
                else
                    call normal_pair_at(seed, -ki, -kj, z1, z2)
                    ak(a, b) = sig*cmplx(z1, -z2, dp)
                end if
                ! expected contributions, counting the conjugate partner of every stored
                ! entry except the ki = 0 column (whose partner is stored itself)
                wt = merge(1.0_dp, 2.0_dp, ki == 0)*2.0_dp*sig**2
                col = col + [wt, wt*(qx*qx + qy*qy)]
            end do
            per_col(:, b) = col
        end do
        !$omp end parallel do
        var_sum = 0.0_dp; slope_sum = 0.0_dp
        do b = 1, size(ak, 2)
            var_sum = var_sum + per_col(1, b); slope_sum = slope_sum + per_col(2, b)
        end do
        if (present(cols)) cols = per_col
    end subroutine random_coefficients

    !> Random surface with spectrum `psd`, scaled to rms slope (sqrt of the slope-tensor trace)
    !> `rms_slope`, or to `rms_height` when rms_slope <= 0. `realised` (default .true.) scales
    !> the realisation itself to the target; otherwise C0 is set from the expectation.
    !> The one transform uses its own FFTW_ESTIMATE plan on one thread made without the process's
    !> wisdom, so the heights are bitwise the same on every run, whatever planner and thread count
    !> the solver uses and whatever was planned before.
    subroutine random_surface(grid, psd, seed, rms_slope, rms_height_target, h, error, realised)
        type(grid_t), intent(in) :: grid
        type(psd_t), intent(in) :: psd
        integer(i8), intent(in) :: seed
        real(dp), intent(in) :: rms_slope, rms_height_target
        real(dp), intent(out) :: h(:, :)
        type(error_t), allocatable, intent(out) :: error
        logical, intent(in), optional :: realised
        type(fft2d_t) :: fft
        real(dp) :: var_sum, slope_sum, scale, m(2, 2), t(2)
        real(dp), allocatable :: cols(:, :)
        logical :: realised_

        realised_ = .true.; if (present(realised)) realised_ = realised
        if (.not. (psd%hurst > 0.0_dp .and. psd%hurst < 1.0_dp)) then
            call fatal_error(error, "hurst must be in (0, 1)"); return
        end if
        if (.not. (psd%eccentricity > 0.0_dp .and. psd%eccentricity <= 1.0_dp)) then
            call fatal_error(error, "eccentricity must be in (0, 1]"); return
        end if
        if (.not. (psd%q_low > 0.0_dp .and. psd%q_low <= psd%q_roll .and. psd%q_roll <= psd%q_cut)) then
            call fatal_error(error, "wavevectors must satisfy 0 < q_low <= q_roll <= q_cut"); return
        end if
        call fft%init(grid%nx, grid%ny, error, isolated=.true., grid=grid); if (allocated(error)) return
        allocate (cols(2, size(fft%k, 2)))
        call random_coefficients(grid, psd, seed, fft%k, var_sum, slope_sum, cols)
        call ordered_sum(grid, cols, t, spectral=.true.)
        var_sum = t(1); slope_sum = t(2)
        if (var_sum <= 0.0_dp) then
            call fatal_error(error, "the spectrum has no mode on this grid (check q_low, q_cut, nx, ny)"); return
        end if
        ! c2r without 1/N: h(x) = sum_q a_q exp(i q.x)
        call fft%backward_unscaled()
        h = fft%x
        h = h - field_mean(grid, h)
        if (realised_) then
            if (rms_slope > 0.0_dp) then
                call slope_tensor(grid, fft, h, m)
                scale = rms_slope/sqrt(m(1, 1) + m(2, 2))
            else
                scale = rms_height_target/field_rms(grid, h)
            end if
        else
            if (rms_slope > 0.0_dp) then
                scale = rms_slope/sqrt(slope_sum)
            else
                scale = rms_height_target/sqrt(var_sum)
            end if
        end if
        h = h*scale
        call fft%destroy()
    end subroutine random_surface

    !> Expected slope tensor of the spectrum on this grid, for unit C0 (sum over modes of q q C)
    pure subroutine expected_slope_tensor(grid, psd, m, var)
        type(grid_t), intent(in) :: grid
        type(psd_t), intent(in) :: psd
        real(dp), intent(out) :: m(2, 2), var
        integer :: ki, kj
        real(dp) :: qx, qy, c
        m = 0.0_dp; var = 0.0_dp
        do kj = -(grid%ny - 1)/2, (grid%ny - 1)/2
            do ki = -(grid%nx - 1)/2, (grid%nx - 1)/2
                if (ki == 0 .and. kj == 0) cycle
                qx = two_pi*ki/grid%lx_m; qy = two_pi*kj/grid%ly_m
                c = two_pi**2/(grid%lx_m*grid%ly_m)*psd_value(psd, qx, qy)
                var = var + c
                m(1, 1) = m(1, 1) + qx*qx*c; m(2, 2) = m(2, 2) + qy*qy*c; m(1, 2) = m(1, 2) + qx*qy*c
            end do
        end do
        m(2, 1) = m(1, 2)
    end subroutine expected_slope_tensor

    !> rms of the heights about their mean
    pure real(dp) function rms_height(h) result(r)
        real(dp), intent(in) :: h(:, :)
        real(dp) :: mean
        mean = sum(h)/size(h)
        r = sqrt(sum((h - mean)**2)/size(h))
    end function rms_height

    !> h = amplitude cos(q.x), q of length 2 pi/wavelength at angle direction_rad from x
    pure subroutine cosine_surface(grid, amplitude, wavelength, direction_rad, h)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: amplitude, wavelength, direction_rad
        real(dp), intent(out) :: h(:, :)
        integer :: i, j
        real(dp) :: qx, qy
        qx = two_pi/wavelength*cos(direction_rad); qy = two_pi/wavelength*sin(direction_rad)
        do j = 1, grid%ny_local
            do i = 1, grid%nx
                h(i, j) = amplitude*cos(qx*(i - 1)*grid%lx_m/grid%nx + qy*(grid%j0 + j - 1)*grid%ly_m/grid%ny)
            end do
        end do
    end subroutine cosine_surface

    !> h = amplitude cos(2 pi x/wavelength) cos(2 pi y/wavelength)
    pure subroutine bisinusoid_surface(grid, amplitude, wavelength, h)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: amplitude, wavelength
        real(dp), intent(out) :: h(:, :)
        integer :: i, j
        do j = 1, grid%ny_local
            do i = 1, grid%nx
                h(i, j) = amplitude*cos(two_pi*(i - 1)*grid%lx_m/grid%nx/wavelength) &
                          *cos(two_pi*(grid%j0 + j - 1)*grid%ly_m/grid%ny/wavelength)
            end do
        end do
    end subroutine bisinusoid_surface

    !> Paraboloid bump h = -r^2/(2R), apex at the cell centre point (nx/2+1, ny/2+1)
    pure subroutine paraboloid_surface(grid, radius, h)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: radius
        real(dp), intent(out) :: h(:, :)
        integer :: i, j
        real(dp) :: x, y
        do j = 1, grid%ny_local
            do i = 1, grid%nx
                x = (i - 1 - grid%nx/2)*grid%lx_m/grid%nx; y = (grid%j0 + j - 1 - grid%ny/2)*grid%ly_m/grid%ny
                h(i, j) = -(x*x + y*y)/(2.0_dp*radius)
            end do
        end do
    end subroutine paraboloid_surface

    !> Cylinder with axis along y: h = -x^2/(2R), apex line at i = nx/2+1
    pure subroutine cylinder_surface(grid, radius, h)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: radius
        real(dp), intent(out) :: h(:, :)
        integer :: i
        real(dp) :: x
        do i = 1, grid%nx
            x = (i - 1 - grid%nx/2)*grid%lx_m/grid%nx
            h(i, 1:grid%ny_local) = -x*x/(2.0_dp*radius)
        end do
    end subroutine cylinder_surface

end module veslide_surface
