!> The validity of a case: numbers that say whether the model and the grid fit the scene, each
!> with a threshold and the reason for it (docs/validity.md), measured after every solve and
!> kept with the result (/validity, the columns of a study's /summary); a measure past its
!> threshold adds a warning to the case (veslide_warning). Before the solve, a surface whose
!> rms slope no small-slope contact model could take is refused (`check_surface_scale`).
!>
!> The measures, with what each guards:
!> - slopes (the half-space's small-slope model): `surface_rms_slope` and
!>   `deformed_rms_slope` (spectral, sqrt of the slope tensor's trace, as &surface rms_slope),
!>   `surface_max_slope_in_contact` and `deformed_max_slope` (central differences);
!> - resolution: `contact_cells` and `contact_patch_cells`, the hydraulic diameter 4 A/P of the
!>   contact in cells (A its cells, P the faces between a contact cell and a free one);
!> - the solid (linear viscoelasticity, and units): `mean_pressure_over_e0`,
!>   `max_pressure_over_e0`, `max_pressure_over_einf` against the contact moduli E/(1 - nu^2);
!> - a measured scan (the height file's preparation): `filled_fraction`,
!>   `band_slope_variance_removed`, `edge_jump_x`, `edge_jump_y`;
!> - whether a modelled ingredient matters: `loss_tan_delta_max` (a viscoelastic solid in motion:
!>   the largest loss tangent over the frequencies the surface excites), `layer_effect` (a layer:
!>   1 - S(q d) at the surface's longest wave, the largest change it makes to a mode's compliance);
!> - an adhesive law's resolution: `adhesion_zone_cells`, its cohesive zone in cells; and its
!>   solver's: `gradient_round_off`, where the adhesive gradient stalled at its round-off over the
!>   tolerance (0: it did not).
module veslide_validity
    use veslide_kinds, only: dp, i8, pi
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: str, sig
    use veslide_grid, only: grid_t
    use veslide_fftw, only: fft2d_t
    use veslide_collective, only: halo_rows, ordered_sum, global_max
    use veslide_fields, only: field_max
    use veslide_material, only: material_t, layer_factor
    use veslide_contact_law, only: contact_law_t
    use veslide_warning, only: warning_t, measure_t, add_warning, add_measure, WARNS_NEVER, WARNS_ABOVE, &
                               WARNS_BELOW
    use veslide_case_data, only: case_t, case_spec_t
    implicit none
    private
    public :: case_validity, check_surface_scale, surface_rms_slope, surface_band, edge_jumps
    public :: slope_warn, slope_refuse, max_slope_warn, contact_cells_min, patch_cells_min, strain_warn, &
              filled_warn, band_removed_warn, edge_jump_limit, loss_warn, zone_cells_min

    !> An rms slope above 0.3: the half-space model takes the surface as flat to first order; the
    !> normal traction it neglects the tilt of grows as slope^2/2 (4.5 % at 0.3; 0.3 is where
    !> rough-contact BEM studies stop trusting the linear half-space, docs/validity.md)
    real(dp), parameter :: slope_warn = 0.3_dp
    !> An rms slope above 10 (84 degrees) is no surface a small-slope contact model can take:
    !> refused (heights in um or nm written as metres, or a channel that is not heights)
    real(dp), parameter :: slope_refuse = 10.0_dp
    !> A slope above 1 (45 degrees) anywhere the solid lies: the tilt error (1 - cos) is 29 %
    real(dp), parameter :: max_slope_warn = 1.0_dp
    !> Resolution: fewer contact cells than this, or patches fewer cells across (hydraulic
    !> diameter) than `patch_cells_min`, and the area and friction are the grid's, not the scene's
    real(dp), parameter :: contact_cells_min = 100.0_dp
    real(dp), parameter :: patch_cells_min = 3.0_dp
    !> The largest pressure above 0.3 of the glassy contact modulus: strains of 0.3 even where the
    !> solid is stiffest, beyond linear (visco)elasticity (and a sign of moduli in the wrong unit)
    real(dp), parameter :: strain_warn = 0.3_dp
    !> A scan more than 2 % filled (unmeasured points interpolated): invented heights can carry
    !> as much contact as the few per cent of the cell that touch
    real(dp), parameter :: filled_warn = 0.02_dp
    !> The band removed more than half of the scan's slope variance: the contact (set by the
    !> slopes) is that of another surface
    real(dp), parameter :: band_removed_warn = 0.5_dp
    !> An edge jump above this many h_rms, and above three times the rms step inside, makes a
    !> file's periodic images step (it is solved as periodic)
    real(dp), parameter :: edge_jump_limit = 0.5_dp
    !> A viscoelastic solid in motion whose loss tangent stays below 1e-3 (the loss of metals)
    !> at every frequency the surface excites responds elastically: the model changes nothing
    real(dp), parameter :: loss_warn = 1.0e-3_dp
    !> An adhesive law whose cohesive zone is below a cell: the discrete problem has several
    !> solutions at one load, its edges trapped between cells. The JKR wave's contact at one load,
    !> reached from a cold start, from above and from below, spread by 0 cells with a zone of 4
    !> cells, 2 at 1 and 2, 14 at 1/2 (12 %) and 22 to 322 at 1/4 (35 to 40 %) (docs/validity.md)
    real(dp), parameter :: zone_cells_min = 1.0_dp

contains

    !> Do the opposite edges of a height file jump (`jump` and `step`: the rms jump across the
    !> edges and the rms step between neighbours inside, in h_rms)?
    elemental logical function edge_jumps(jump, step) result(yes)
        real(dp), intent(in) :: jump, step
        yes = jump > edge_jump_limit .and. jump > 3.0_dp*step
    end function edge_jumps

    !> The rms slope sqrt(<|grad h|^2>) of `h` on `grid`, spectral: the trace of the slope tensor
    !> (veslide_spectrum's, to round-off; &surface rms_slope is defined so), summed here in one
    !> pass over the half-spectrum; uses the buffers of `fft`
    real(dp) function surface_rms_slope(grid, fft, h) result(s)
        type(grid_t), intent(in) :: grid
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: h(:, :)
        real(dp) :: q(2), cols(1, size(fft%k, 2)), t(1), c
        real(dp) :: qx2(grid%nq()), qy2(grid%ny), w(grid%nq())
        integer :: a, b, i, j
        fft%x = h
        call fft%forward()
        do i = 1, grid%nq()
            q = grid%derivative_wavevector(i, 1); qx2(i) = q(1)**2; w(i) = grid%hermitian_weight(i)
        end do
        do j = 1, grid%ny
            q = grid%derivative_wavevector(1, j); qy2(j) = q(2)**2
        end do
        associate (k => fft%k)
            !$omp parallel do schedule(static) private(a, i, j, c)
            do b = 1, size(k, 2)
                c = 0.0_dp
                if (grid%transposed) then            ! (ny, nq_local): row i0 + b, column a
                    i = grid%i0 + b
                    do a = 1, size(k, 1)
                        c = c + (qx2(i) + qy2(a))*(real(k(a, b), dp)**2 + aimag(k(a, b))**2)
                    end do
                    c = c*w(i)
                else                                 ! (nx/2 + 1, ny): row a, column b
                    do a = 1, size(k, 1)
                        c = c + w(a)*(qx2(a) + qy2(b))*(real(k(a, b), dp)**2 + aimag(k(a, b))**2)
                    end do
                end if
                cols(1, b) = c
            end do
            !$omp end parallel do
        end associate
        call ordered_sum(grid, cols, t, spectral=.true.)
        s = sqrt(max(t(1), 0.0_dp))/grid%cells()
    end function surface_rms_slope

    !> The band of |q| the surface of `spec` holds [1/m]: its spectrum's for a random surface, its
    !> wave's for a cosine or a bisinusoid, q0 to the grid's Nyquist otherwise
    pure subroutine surface_band(spec, grid, qlo, qhi)
        type(case_spec_t), intent(in) :: spec
        type(grid_t), intent(in) :: grid
        real(dp), intent(out) :: qlo, qhi
        qlo = grid%q0(); qhi = 0.5_dp*grid%nx*grid%q0()
        select case (spec%surface%kind)
        case ('self_affine')
            qlo = spec%surface%k_low*grid%q0(); qhi = spec%surface%k_cut*grid%q0()
        case ('cosine')
            qlo = 2.0_dp*pi/spec%surface%wavelength_m; qhi = qlo
        case ('bisinusoid')
            qlo = sqrt(2.0_dp)*2.0_dp*pi/spec%surface%wavelength_m; qhi = qlo
        end select
    end subroutine surface_band

    !> Refuse a surface no small-slope contact model can take: an rms slope above `slope_refuse`
    !> (not for the single asperities, paraboloid and cylinder, whose slopes far from the apex
    !> never touch); the message names the input and the likely cause. `rms_slope` is the rms
    !> slope measured, which the case keeps for its validity measures (one transform per surface)
    subroutine check_surface_scale(spec, grid, fft, h, error, rms_slope)
        type(case_spec_t), intent(in) :: spec
        type(grid_t), intent(in) :: grid
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: h(:, :)
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(out), optional :: rms_slope
        real(dp) :: s
        character(len=:), allocatable :: at
        s = surface_rms_slope(grid, fft, h)
        if (present(rms_slope)) rms_slope = s
        select case (spec%surface%kind)
        case ('paraboloid', 'cylinder', 'flat')
            return
        end select
        if (.not. s > slope_refuse) return
        at = "veslide: "//spec%input_path//": &surface "
        select case (spec%surface%kind)
        case ('file')
            call fatal_error(error, at//"file '"//spec%surface%file//"': the rms slope of its heights is "// &
                sig(s, 2)//" (at most "//sig(slope_refuse)//"; a contact of small slopes needs well below 1):"// &
                " heights in um or nm written as metres, or a channel that is not heights? (python -m veslide"// &
                " topography SCAN --unit, --channel)")
        case ('self_affine')
            call fatal_error(error, at//"rms_height_m = "//sig(spec%surface%rms_height_m)//" gives an rms slope of "// &
                sig(s, 2)//" on this cell (at most "//sig(slope_refuse)//"; a contact of small slopes needs well"// &
                " below 1): rms_height_m in metres? (or set rms_slope)")
        case default
            call fatal_error(error, at//"amplitude_m = "//sig(spec%surface%amplitude_m)//" over wavelength_m = "// &
                sig(spec%surface%wavelength_m)//" gives an rms slope of "//sig(s, 2)//" (at most "// &
                sig(slope_refuse)//"; a contact of small slopes needs well below 1): lengths in metres?")
        end select
    end subroutine check_surface_scale

    !> The validity measures of a solved case and the warnings of those past their thresholds:
    !> c%validity, and c%warnings = the input's warnings, then the case's own. Uses the buffers
    !> of `fft` (after the solve and its force); collective on a distributed grid.
    subroutine case_validity(c, fft)
        type(case_t), intent(inout) :: c
        type(fft2d_t), intent(inout) :: fft
        real(dp) :: rms_h, rms_u, stats(4), e0s, einfs, pmax, patch, qlo, qhi, cells_min
        integer(i8) :: ncontact
        logical :: one_row
        character(len=:), allocatable :: what
        if (allocated(c%validity)) deallocate (c%validity)
        if (allocated(c%warnings)) deallocate (c%warnings)
        allocate (c%validity(0), c%warnings(0))
        if (allocated(c%spec%warnings)) c%warnings = c%spec%warnings
        associate (solid => c%spec%material%solid, kind => c%spec%surface%kind)

            ! slopes: the small-slope half-space
            rms_h = c%surface_rms_slope                  ! (measured when the surface was checked)
            if (rms_h < 0.0_dp) rms_h = surface_rms_slope(c%grid, fft, c%h)
            rms_u = surface_rms_slope(c%grid, fft, c%state%u)
            call contact_statistics(c%grid, c%spec%law, c%state%p, c%state%g, c%h, c%state%u, stats)
            ncontact = nint(stats(1), i8)
            if (kind == 'paraboloid' .or. kind == 'cylinder' .or. kind == 'flat') then
                call measure('surface_rms_slope', rms_h, '-')    ! (its slopes far from the apex never touch)
            else
                call measure('surface_rms_slope', rms_h, '-', WARNS_ABOVE, slope_warn, 'surface-slope', &
                    "the rigid surface's rms slope is "//sig(rms_h)//", above "//sig(slope_warn)//": the half-space"// &
                    " model takes slopes as small (its normal traction errs by about slope^2/2 = "// &
                    sig(50.0_dp*rms_h**2, 2)//" %); the contact of so steep a surface is outside the model")
            end if
            call measure('surface_max_slope_in_contact', stats(3), '-', WARNS_ABOVE, max_slope_warn, &
                'surface-slope', "the rigid surface's slope reaches "//sig(stats(3))//" where it touches, above "// &
                sig(max_slope_warn)//" (45 degrees): the small-slope half-space model does not hold there")
            call measure('deformed_rms_slope', rms_u, '-', WARNS_ABOVE, slope_warn, 'deformed-slope', &
                "the deformed solid's rms slope is "//sig(rms_u)//", above "//sig(slope_warn)//": the half-space"// &
                " model takes its surface as nearly flat; the load deforms it beyond that")
            call measure('deformed_max_slope', stats(4), '-', WARNS_ABOVE, max_slope_warn, 'deformed-slope', &
                "the deformed solid's slope reaches "//sig(stats(4))//", above "//sig(max_slope_warn)// &
                " (45 degrees): the small-slope half-space model does not hold there")

            ! resolution of the contact: its cells, and its patches' hydraulic diameter 4 A/P in
            ! cells (a profile, ny = 1: the mean length 2 A/P of its contact segments)
            one_row = c%grid%ny == 1
            cells_min = contact_cells_min
            if (one_row) cells_min = sqrt(contact_cells_min)     ! (as many cells across as in 2-D)
            patch = 0.0_dp
            if (stats(2) > 0.0_dp) patch = merge(2.0_dp, 4.0_dp, one_row)*stats(1)/stats(2)
            if (stats(2) == 0.0_dp .and. ncontact > 0) patch = real(c%grid%nx, dp)     ! full contact
            call add_measure(c%validity, 'contact_cells', real(ncontact, dp), '-', WARNS_BELOW, cells_min, &
                             is_integer=.true.)
            call add_measure(c%validity, 'contact_patch_cells', patch, '-', WARNS_BELOW, patch_cells_min)
            if (real(ncontact, dp) < cells_min .or. patch < patch_cells_min) call resolution_warning()

            ! the solid: linear viscoelasticity, and units
            e0s = solid%e0_pa/(1.0_dp - solid%poisson**2)
            einfs = solid%einf_pa/(1.0_dp - solid%poisson**2)
            pmax = field_max(c%grid, c%state%p)
            call measure('mean_pressure_over_e0', c%spec%mean_pressure_pa/e0s, '-')
            call measure('max_pressure_over_e0', pmax/e0s, '-')
            call measure('max_pressure_over_einf', pmax/einfs, '-', WARNS_ABOVE, strain_warn, 'pressure-strain', &
                "the largest pressure is "//sig(pmax/einfs)//" of the solid's glassy contact modulus Einf/(1 - nu^2)"// &
                " = "//sig(einfs)//" Pa, above "//sig(strain_warn)//": strains that large lie beyond linear"// &
                " (visco)elasticity (a modulus in kPa or MPa read as Pa?)")

            ! a measured scan: what its preparation cost
            if (kind == 'file') then
                if (c%spec%surface%filled_fraction >= 0.0_dp) &
                    call measure('filled_fraction', c%spec%surface%filled_fraction, '-', WARNS_ABOVE, filled_warn, &
                        'filled-scan', "'"//c%spec%surface%file//"' was "// &
                        sig(100.0_dp*c%spec%surface%filled_fraction)//" % unmeasured and filled by interpolation"// &
                        " (above "//sig(100.0_dp*filled_warn)//" %): invented heights can carry the contact; prepare"// &
                        " the scan with --crop-valid (its largest measured rectangle)")
                if (c%spec%surface%band_slope_removed >= 0.0_dp) &
                    call measure('band_slope_variance_removed', c%spec%surface%band_slope_removed, '-', WARNS_ABOVE, &
                        band_removed_warn, 'band-slope-removed', "the band of '"//c%spec%surface%file// &
                        "' removed "//sig(100.0_dp*c%spec%surface%band_slope_removed)//" % of the scan's slope"// &
                        " variance (above "//sig(100.0_dp*band_removed_warn)//" %): the contact is that of a smoother"// &
                        " surface; prepare it on a finer grid (python -m veslide topography SCAN --nx ...)")
                ! (the edges warn once, when the input is read)
                call add_measure(c%validity, 'edge_jump_x', c%spec%surface%edge_jump(1), '-', WARNS_ABOVE, &
                                 edge_jump_limit)
                call add_measure(c%validity, 'edge_jump_y', c%spec%surface%edge_jump(2), '-', WARNS_ABOVE, &
                                 edge_jump_limit)
            end if

            ! does each modelled ingredient matter here?
            call surface_band(c%spec, c%grid, qlo, qhi)
            if (.not. solid%is_elastic() .and. c%spec%speed_m_s > 0.0_dp) call loss_measure()
            if (solid%thickness_m > 0.0_dp) then
                what = "the layer changes no mode's compliance by more than "
                call measure('layer_effect', 1.0_dp - solid%layer(qlo*solid%thickness_m), '-', WARNS_BELOW, &
                    c%spec%solver%tolerance, 'layer-no-effect', what// &
                    sig(1.0_dp - solid%layer(qlo*solid%thickness_m), 2)//" (q d = "// &
                    sig(qlo*solid%thickness_m)//" at the surface's longest wave; below the solver's tolerance "// &
                    sig(c%spec%solver%tolerance, 2)//"): a half-space (thickness_m = 0) gives the same result")
            end if

            ! an adhesive law: is its cohesive zone resolved by the grid? can the solver's
            ! gradient be resolved to the tolerance asked?
            if (c%spec%law%adhesive()) call zone_measure()
            if (c%spec%law%adhesive() .and. c%state%method == 'gcg') then
                call measure('gradient_round_off', c%state%round_off/c%spec%solver%tolerance, '-', WARNS_ABOVE, &
                    1.0_dp, 'tolerance-below-round-off', "the adhesive solver's gradient stopped falling at "// &
                    sig(c%state%round_off, 2)//" of the pressure scale, its round-off on this grid (which grows"// &
                    " with the finest wavenumber), above &solver tolerance "//sig(c%spec%solver%tolerance, 2)// &
                    ": the case converged only if the problem's residual met the tolerance; a tolerance of "// &
                    sig(2.0_dp*c%state%round_off, 1)//" or more asks for what double precision can give")
            end if

            ! an adhesive law under load control: a load the branch followed cannot carry although
            ! the law is met (to a tenth of the load's error, as the secant's inner solves are) at
            ! every mean gap tried (the load jumps where a contact snaps in or out; docs/adhesion.md)
            if (c%spec%law%adhesive() .and. .not. c%state%converged .and. c%spec%approach_m == huge(1.0_dp)) then
                if (max(c%state%penetration, c%state%complementarity, c%state%negative_pressure) <= &
                    max(c%spec%solver%tolerance, 0.1_dp*c%state%load_error) .and. &
                    c%state%load_error > c%spec%solver%tolerance) &
                    call add_warning(c%warnings, 'adhesive-load-jump', "the law is met but the load is off by "// &
                        sig(c%state%load_error, 2)//" of the pressure scale: the load lies where the load jumps"// &
                        " with the approach (a contact snapping in or out), so the branch followed has no solution"// &
                        " at it; give the approach instead (&load approach_m, or &sweep approaches_m for a path)"// &
                        " or another load", 'validity', &
                        c%state%load_error, c%spec%solver%tolerance)
            end if
        end associate

    contains

        !> Add a measure, and its warning (`code`, `text`) when it is past its threshold
        subroutine measure(name, value, units, warns, threshold, code, text)
            character(len=*), intent(in) :: name, units
            real(dp), intent(in) :: value
            integer, intent(in), optional :: warns
            real(dp), intent(in), optional :: threshold
            character(len=*), intent(in), optional :: code, text
            logical :: past
            call add_measure(c%validity, name, value, units, warns, threshold)
            if (.not. present(code)) return
            past = (warns == WARNS_ABOVE .and. value > threshold) .or. (warns == WARNS_BELOW .and. value < threshold)
            if (past) call add_warning(c%warnings, code, text, 'validity', value, threshold)
        end subroutine measure

        !> The contact is too small for its grid: say how small, and the grid that would resolve it
        subroutine resolution_warning()
            real(dp) :: factor, value, threshold
            integer :: n_fine
            character(len=:), allocatable :: next
            factor = 1.0_dp
            if (patch > 0.0_dp) factor = max(factor, patch_cells_min/patch)
            if (ncontact > 0 .and. one_row) factor = max(factor, cells_min/real(ncontact, dp))
            if (ncontact > 0 .and. .not. one_row) factor = max(factor, sqrt(cells_min/real(ncontact, dp)))
            n_fine = 2**ceiling(log(real(c%grid%nx, dp)*factor)/log(2.0_dp) - 1.0e-9_dp)
            if (n_fine <= c%grid%nx) n_fine = 2*c%grid%nx
            if (c%spec%surface%kind == 'file') then
                next = "prepare the scan on a finer grid (python -m veslide topography SCAN --nx "//str(n_fine)//")"
            else
                next = "a grid of "//str(n_fine)//" cells along x would resolve it; veslide.refine (python -m veslide"// &
                       " refine INPUT "//str(c%grid%nx)//" "//str(2*c%grid%nx)//" ...) gives the error band"
            end if
            if (real(ncontact, dp) < cells_min) then
                value = real(ncontact, dp); threshold = cells_min
            else
                value = patch; threshold = patch_cells_min
            end if
            call add_warning(c%warnings, 'contact-resolution', "the contact covers "//str(ncontact)// &
                " cells, its patches "//sig(patch, 2)//" cells across (at least "//sig(cells_min)// &
                " cells and "//sig(patch_cells_min)//" across to quote the area and the friction): "// &
                "the result is the grid's as much as the scene's; "//next, 'validity', value, threshold)
        end subroutine resolution_warning

        !> The adhesive law's cohesive zone in cells: l = pi E0* w/(4 sigma0^2), the length over
        !> which the attraction acts beside a contact edge (Maugis's and Dugdale's zone in the JKR
        !> limit, with sigma0 = w/rho for the exponential law), on the relaxed contact modulus E0* =
        !> E0/(1 - nu^2) (the softest: the shortest zone), over the larger side of a cell; a
        !> half-space's zone (a layer thinner than the zone stiffens it and shortens it)
        subroutine zone_measure()
            real(dp) :: zone, cell, d(2)
            d = c%grid%spacing()
            cell = d(1)
            if (c%grid%ny > 1) cell = max(d(1), d(2))
            zone = c%spec%law%zone(e0s)
            call measure('adhesion_zone_cells', zone/cell, '-', WARNS_BELOW, zone_cells_min, &
                'adhesion-zone-unresolved', "the adhesive law's cohesive zone, pi E0* w/(4 sigma0^2) = "// &
                sig(zone)//" m, is "//sig(zone/cell, 2)//" of a cell (below "//sig(zone_cells_min)// &
                "): the contact's edges are trapped between cells, and the contact at a load depends on"// &
                " the path to it (the JKR wave's by 12 % at half a cell, by 35 to 130 % at a quarter and"// &
                " below; docs/validity.md); refine the grid, or widen the range (&adhesion range_m)")
        end subroutine zone_measure

        !> The largest loss tangent over the frequencies |q| v the surface excites (q in its band)
        subroutine loss_measure()
            integer, parameter :: n = 256
            real(dp) :: w, td, best, wpeak, tdpeak, lo, hi
            complex(dp) :: cc
            integer :: k
            lo = log(qlo*c%spec%speed_m_s); hi = log(qhi*c%spec%speed_m_s)
            best = 0.0_dp
            do k = 0, n
                w = exp(lo + (hi - lo)*k/n)
                cc = c%spec%material%solid%compliance(w)
                td = -aimag(cc)/real(cc, dp)
                best = max(best, td)
            end do
            call c%spec%material%solid%loss_peak(wpeak, tdpeak)
            if (wpeak >= exp(lo) .and. wpeak <= exp(hi)) best = max(best, tdpeak)
            call measure('loss_tan_delta_max', best, '-', WARNS_BELOW, loss_warn, 'negligible-loss', &
                "the loss tangent is at most "//sig(best, 2)//" over the frequencies the surface excites at "// &
                sig(c%spec%speed_m_s)//" m/s ("//sig(exp(lo))//" to "//sig(exp(hi))//" rad/s; its peak "// &
                sig(tdpeak)//" lies at "//sig(wpeak)//" rad/s): below "//sig(loss_warn)//" the solid responds"// &
                " elastically and the viscoelastic model changes nothing but a friction near zero")
        end subroutine loss_measure
    end subroutine case_validity

    !> Sums and extrema of the contact (the contact cells of the pressure p, by the contact law
    !> `law`) in one pass over the rows: [contact cells, faces between a contact cell and a free
    !> one, the largest slope of h over the contact cells, the largest slope of u over the cell]
    !> (central differences; periodic; collective on a distributed grid, whose neighbouring rows
    !> come from the other processes)
    subroutine contact_statistics(grid, law, p, g, h, u, stats)
        type(grid_t), intent(in) :: grid
        type(contact_law_t), intent(in) :: law
        !> pressure and gap (an adhesive law's contact is where the gap is closed)
        real(dp), intent(in) :: p(:, :), g(:, :), h(:, :), u(:, :)
        real(dp), intent(out) :: stats(4)
        real(dp), allocatable :: pe(:, :), ge(:, :), he(:, :), ue(:, :)
        logical, allocatable :: ce(:, :), cl(:, :)
        real(dp) :: rows(2, size(p, 2)), peak(2, size(p, 2)), t(2)
        integer :: j, nl
        nl = size(p, 2)
        if (grid%is_distributed()) then
            call halo_rows(grid, p, 1, pe); call halo_rows(grid, h, 1, he); call halo_rows(grid, u, 1, ue)
            call halo_rows(grid, g, 1, ge)
            allocate (ce(size(pe, 1), lbound(pe, 2):ubound(pe, 2)))
            ce = law%contact(pe, ge)
            !$omp parallel do schedule(static)
            do j = 1, nl
                call row_statistics(grid, ce(:, j - 1:j + 1), he(:, j - 1:j + 1), ue(:, j - 1:j + 1), &
                                    rows(:, j), peak(:, j))
            end do
            !$omp end parallel do
        else                    ! one process: the neighbouring rows are the periodic ones
            cl = law%contact(p, g)
            !$omp parallel do schedule(static)
            do j = 1, nl
                call row_statistics(grid, cl(:, [modulo(j - 2, nl) + 1, j, modulo(j, nl) + 1]), &
                                    h(:, [modulo(j - 2, nl) + 1, j, modulo(j, nl) + 1]), &
                                    u(:, [modulo(j - 2, nl) + 1, j, modulo(j, nl) + 1]), rows(:, j), peak(:, j))
            end do
            !$omp end parallel do
        end if
        call ordered_sum(grid, rows, t)
        stats(1:2) = t
        stats(3) = 0.0_dp; stats(4) = 0.0_dp
        if (nl > 0) then
            stats(3) = sqrt(maxval(peak(1, :))); stats(4) = sqrt(maxval(peak(2, :)))
        end if
        call global_max(grid, stats(3)); call global_max(grid, stats(4))
    end subroutine contact_statistics

    !> One row's part of contact_statistics from the rows below, at and above it (columns 1, 2,
    !> 3 of the contact cells c, h, u): its contact cells and contact edge faces (to the right and
    !> above), and the largest squared slopes of h over its contact cells and of u
    pure subroutine row_statistics(grid, c, h, u, sums, peak)
        type(grid_t), intent(in) :: grid
        logical, intent(in) :: c(:, :)
        real(dp), intent(in) :: h(:, :), u(:, :)
        real(dp), intent(out) :: sums(2), peak(2)
        real(dp) :: cx, cy, s2, cells, faces
        integer :: nx, i, ip, im
        logical :: in, two_d
        nx = size(c, 1)
        cx = 0.5_dp*grid%nx/grid%lx_m; cy = 0.5_dp*grid%ny/grid%ly_m     ! 1/(2 dx), 1/(2 dy)
        two_d = grid%ny > 1
        cells = 0.0_dp; faces = 0.0_dp; peak = 0.0_dp
        do i = 1, nx
            ip = i + 1; if (i == nx) ip = 1
            im = i - 1; if (i == 1) im = nx
            in = c(i, 2)
            if (in) cells = cells + 1.0_dp
            if (in .neqv. c(ip, 2)) faces = faces + 1.0_dp
            if (two_d .and. (in .neqv. c(i, 3))) faces = faces + 1.0_dp
            s2 = (cx*(u(ip, 2) - u(im, 2)))**2
            if (two_d) s2 = s2 + (cy*(u(i, 3) - u(i, 1)))**2
            peak(2) = max(peak(2), s2)
            if (in) then
                s2 = (cx*(h(ip, 2) - h(im, 2)))**2
                if (two_d) s2 = s2 + (cy*(h(i, 3) - h(i, 1)))**2
                peak(1) = max(peak(1), s2)
            end if
        end do
        sums = [cells, faces]
    end subroutine row_statistics

end module veslide_validity
