!> The validity of a case (veslide_validity): each measure against an oracle where one exists,
!> and each threshold crossed by a case built to cross it and not by one built not to; the
!> refusals of what no input can be, each naming the input and the likely cause; warnings kept
!> with the case, its study rows and its file.
module test_veslide_validity
    use veslide_kinds, only: dp, i8, pi
    use veslide_config, only: config_t
    use veslide_case, only: case_t, run_case
    use veslide_case_file, only: write_case
    use veslide_hdf5, only: h5file_t
    use veslide_study, only: run_study
    use veslide_warning, only: measure_t
    use veslide_validity, only: slope_warn, max_slope_warn, contact_cells_min, patch_cells_min, strain_warn, &
                                filled_warn, band_removed_warn, loss_warn
    use testsuite, only: error_t, unittest_t, new_unittest, check
    use test_support, only: unique_name, remove
    use test_veslide_config, only: read_text, expect_words
    use test_veslide_topography, only: write_heights
    implicit none
    private
    public :: collect_validity

    !> a small scene that solves fast and warns of nothing: 128^2, 8 cells per shortest wave
    character(len=*), parameter :: sound = "&grid nx = 128, ny = 128 / &surface k_cut = 16 /"// &
                                           " &solver fft_planner = 'estimate' / "

contains

    subroutine collect_validity(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("sound-scene-warns-of-nothing", test_sound), &
            new_unittest("surface-rms-slope-is-the-input-and-the-cosine", test_rms_slope_oracle), &
            new_unittest("surface-slope-warns-above-0.3", test_surface_slope), &
            new_unittest("slope-in-contact-warns-above-1", test_contact_slope), &
            new_unittest("deformed-slope-is-the-surface-in-full-contact", test_deformed_slope), &
            new_unittest("contact-of-few-cells-warns", test_contact_cells), &
            new_unittest("patches-of-few-cells-warn", test_patch_cells), &
            new_unittest("patch-size-of-a-disc-and-a-stripe", test_patch_oracle), &
            new_unittest("profile-resolution-counts-along-x", test_profile_resolution), &
            new_unittest("pressure-near-the-glassy-modulus-warns", test_pressure_strain), &
            new_unittest("filled-scan-warns", test_filled), &
            new_unittest("band-removal-warns", test_band_removed), &
            new_unittest("negligible-loss-warns", test_loss), &
            new_unittest("layer-without-effect-warns", test_layer), &
            new_unittest("rms-slope-above-10-refused-file", test_refuse_file), &
            new_unittest("rms-slope-above-10-refused-generated", test_refuse_generated), &
            new_unittest("modulus-below-1-pa-refused", test_refuse_modulus), &
            new_unittest("pressure-above-glassy-modulus-refused", test_refuse_pressure), &
            new_unittest("generator-settings-with-a-file-warn", test_unused_surface), &
            new_unittest("settings-of-another-model-warn", test_unused_material), &
            new_unittest("warnings-in-the-file", test_file_warnings), &
            new_unittest("warnings-per-study-case-and-counted", test_study_warnings) &
            ]
    end subroutine collect_validity

    ! ---------------------------------------------------------------- helpers

    !> Solve the case of namelist `text`
    subroutine solve(tag, text, c, error)
        character(len=*), intent(in) :: tag, text
        type(case_t), intent(out) :: c
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text(tag, text, cfg, error); if (allocated(error)) return
        call run_case(cfg, c, error)
        if (allocated(error)) return
        call check(error, c%state%converged, tag//": not converged")
    end subroutine solve

    !> The value of measure `name` of a solved case (huge() when absent)
    real(dp) function measure(c, name) result(v)
        type(case_t), intent(in) :: c
        character(len=*), intent(in) :: name
        integer :: k
        v = huge(1.0_dp)
        do k = 1, size(c%validity)
            if (c%validity(k)%name == name) v = c%validity(k)%value
        end do
    end function measure

    !> Does the case carry a warning of `code`?
    logical function warns(c, code) result(yes)
        type(case_t), intent(in) :: c
        character(len=*), intent(in) :: code
        integer :: k
        yes = .false.
        do k = 1, size(c%warnings)
            if (c%warnings(k)%code == code) yes = .true.
        end do
    end function warns

    !> The codes of a case's warnings, for messages
    function codes(c) result(t)
        type(case_t), intent(in) :: c
        character(len=:), allocatable :: t
        integer :: k
        t = 'warnings:'
        do k = 1, size(c%warnings)
            t = t//' '//c%warnings(k)%code
        end do
    end function codes

    !> A case crossing a threshold and one not: `yes` must warn of `code`, `no` must not
    subroutine crossing(yes, no, code, error)
        type(case_t), intent(in) :: yes, no
        character(len=*), intent(in) :: code
        type(error_t), allocatable, intent(out) :: error
        call check(error, warns(yes, code), "the case built to cross does not warn of "//code//"; "//codes(yes))
        if (allocated(error)) return
        call check(error, .not. warns(no, code), "the case built not to cross warns of "//code//"; "//codes(no))
    end subroutine crossing


    ! ---------------------------------------------------------------- measures

    !> A resolved self-affine contact (128^2, 8 cells per shortest wave), at rest and sliding:
    !> every measure in range, no warning
    subroutine test_sound(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: c
        call solve('sound', sound, c, error); if (allocated(error)) return
        call check(error, size(c%warnings) == 0, "an elastic contact warns: "//codes(c)); if (allocated(error)) return
        call solve('sound', sound//" &material model = 'one_term' / &motion speed_m_s = 0.13 /", c, error)
        if (allocated(error)) return
        call check(error, size(c%warnings) == 0, "a sliding contact warns: "//codes(c)); if (allocated(error)) return
        call check(error, size(c%validity) == 10, "the ten measures of a sliding half-space")
    end subroutine test_sound

    !> The rigid surface's rms slope is the spectral one: a self-affine surface scaled to
    !> rms_slope has it to round-off; a cosine A cos(q x) has A q/sqrt(2)
    subroutine test_rms_slope_oracle(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: c
        real(dp) :: a, q
        call solve('rmsoracle', "&grid nx = 128, ny = 128 / &surface k_cut = 16, rms_slope = 0.04 /"// &
                   " &solver fft_planner = 'estimate' /", c, error)
        if (allocated(error)) return
        call check(error, measure(c, 'surface_rms_slope'), 0.04_dp, "realised rms slope", rel=1.0e-13_dp)
        if (allocated(error)) return
        a = 2.0e-5_dp; q = 2.0_dp*pi/2.5e-3_dp
        call solve('rmscos', "&grid nx = 64, ny = 64 / &surface kind = 'cosine', amplitude_m = 2e-5,"// &
                   " wavelength_m = 2.5e-3 / &load mean_pressure_pa = 1e5 / &solver fft_planner = 'estimate' /", c, error)
        if (allocated(error)) return
        call check(error, measure(c, 'surface_rms_slope'), a*q/sqrt(2.0_dp), "cosine A q/sqrt 2", rel=1.0e-13_dp)
    end subroutine test_rms_slope_oracle

    !> A cosine of rms slope 0.35 warns (above 0.3), one of 0.25 does not
    subroutine test_surface_slope(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        call solve('slopey', cosine(0.35_dp), yes, error); if (allocated(error)) return
        call solve('slopen', cosine(0.25_dp), no, error); if (allocated(error)) return
        call check(error, measure(yes, 'surface_rms_slope') > slope_warn .and. measure(no, 'surface_rms_slope') < &
                   slope_warn, "the two cases straddle the threshold"); if (allocated(error)) return
        call crossing(yes, no, 'surface-slope', error)
    end subroutine test_surface_slope

    !> A cosine of rms slope `s` (wavelength 2.5 mm on a 1 cm cell of 64^2) on a solid of Young's
    !> modulus `young_pa` (default 1e9, stiff enough to leave small contacts) under `pressure_pa`
    !> (default 1 MPa)
    function cosine(s, young_pa, pressure_pa) result(text)
        real(dp), intent(in) :: s
        character(len=*), intent(in), optional :: young_pa, pressure_pa
        character(len=:), allocatable :: text, e, p
        character(len=32) :: amp
        e = '1e9'; if (present(young_pa)) e = young_pa
        p = '1e6'; if (present(pressure_pa)) p = pressure_pa
        write (amp, '(es12.5)') s*sqrt(2.0_dp)*2.5e-3_dp/(2.0_dp*pi)
        text = "&grid nx = 64, ny = 64 / &surface kind = 'cosine', amplitude_m = "//trim(amp)// &
               ", wavelength_m = 2.5e-3 / &material young_pa = "//e//" / &load mean_pressure_pa = "//p//" /"// &
               " &solver fft_planner = 'estimate' /"
    end function cosine

    !> A paraboloid pressed until its contact radius exceeds its radius of curvature (the slope
    !> a/R > 1 at the edge of contact) warns; lightly pressed it does not
    subroutine test_contact_slope(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        character(len=*), parameter :: ball = "&grid nx = 128, ny = 128, lx_m = 0.01 / &surface kind = 'paraboloid',"// &
            " radius_m = 1e-3 / &material young_pa = 1e7 / &solver fft_planner = 'estimate' /"
        call solve('cslopey', ball//" &load mean_pressure_pa = 5e5 /", yes, error); if (allocated(error)) return
        call solve('cslopen', ball//" &load mean_pressure_pa = 2e3 /", no, error); if (allocated(error)) return
        call check(error, measure(yes, 'surface_max_slope_in_contact') > max_slope_warn .and. &
                   measure(no, 'surface_max_slope_in_contact') < max_slope_warn, "the two cases straddle 1")
        if (allocated(error)) return
        call check(error, measure(yes, 'surface_rms_slope') > slope_warn .and. .not. warns(no, 'surface-slope'), &
                   "the paraboloid's rms slope over the cell (never touched) must not warn")
        if (allocated(error)) return
        call crossing(yes, no, 'surface-slope', error)
    end subroutine test_contact_slope

    !> In full contact the solid takes the surface's shape: its rms slope is the surface's (to the
    !> solver's tolerance); a steep cosine in full contact warns of both, a gentle one of neither
    subroutine test_deformed_slope(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        call solve('dslopey', cosine(0.4_dp, '1e6', '5e5'), yes, error); if (allocated(error)) return
        call solve('dslopen', cosine(0.1_dp, '1e6', '5e5'), no, error); if (allocated(error)) return
        call check(error, measure(yes, 'contact_cells') == 64.0_dp**2 .and. measure(no, 'contact_cells') == &
                   64.0_dp**2, "full contact"); if (allocated(error)) return
        call check(error, measure(yes, 'deformed_rms_slope'), measure(yes, 'surface_rms_slope'), &
                   "deformed = surface in full contact", rel=1.0e-8_dp); if (allocated(error)) return
        call crossing(yes, no, 'deformed-slope', error)
    end subroutine test_deformed_slope

    !> A contact of a few cells (the default scene at 64^2 under 100 Pa) warns, naming the grid
    !> that would resolve it and refine; the sound scene does not
    subroutine test_contact_cells(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        integer :: k
        call solve('fewy', "&grid nx = 64, ny = 64 / &surface k_cut = 8 / &load mean_pressure_pa = 100 /"// &
                   " &solver fft_planner = 'estimate' /", yes, error); if (allocated(error)) return
        call solve('fewn', sound, no, error); if (allocated(error)) return
        call check(error, measure(yes, 'contact_cells') < contact_cells_min .and. measure(no, 'contact_cells') > &
                   contact_cells_min, "the two cases straddle 100 cells"); if (allocated(error)) return
        call crossing(yes, no, 'contact-resolution', error); if (allocated(error)) return
        do k = 1, size(yes%warnings)
            if (yes%warnings(k)%code /= 'contact-resolution') cycle
            call check(error, index(yes%warnings(k)%text, 'refine') > 0 .and. index(yes%warnings(k)%text, &
                       'cells along x would resolve it') > 0, yes%warnings(k)%text); if (allocated(error)) return
            call check(error, yes%warnings(k)%value == measure(yes, 'contact_cells') .and. &
                       yes%warnings(k)%threshold == contact_cells_min, "the warning's value and threshold")
        end do
    end subroutine test_contact_cells

    !> Many cells in patches of about two cells (the sliding scene at 64^2 with four cells per
    !> shortest wave) warn; the same surface on 128^2 with eight does not
    subroutine test_patch_cells(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        character(len=*), parameter :: sliding = " &material model = 'one_term' / &motion speed_m_s = 0.13 /"
        call solve('patchy', "&grid nx = 64, ny = 64 / &surface k_cut = 16 / &solver fft_planner = 'estimate' /"// &
                   sliding, yes, error); if (allocated(error)) return
        call solve('patchn', sound//sliding, no, error); if (allocated(error)) return
        call check(error, measure(yes, 'contact_cells') > contact_cells_min .and. measure(yes, &
                   'contact_patch_cells') < patch_cells_min .and. measure(no, 'contact_patch_cells') > patch_cells_min, &
                   "the two cases straddle 3 cells across with over 100 cells"); if (allocated(error)) return
        call crossing(yes, no, 'contact-resolution', error)
    end subroutine test_patch_cells

    !> The patch size is the hydraulic diameter 4 A/P in cells: a bisinusoid's contact under a
    !> light load is two discs (4 A/P of a digital disc of radius r is about pi r/2 ... r, within
    !> the staircase); a cylinder's contact is a stripe across y, 2 wide-sides, 4 A/P = 2 w
    subroutine test_patch_oracle(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: c
        real(dp) :: w
        call solve('stripe', "&grid nx = 256, ny = 16, lx_m = 0.01, ly_m = 6.25e-4 / &surface kind = 'cylinder',"// &
                   " radius_m = 0.05 / &material young_pa = 1e7 / &load mean_pressure_pa = 2e4 /"// &
                   " &solver fft_planner = 'estimate' /", c, error); if (allocated(error)) return
        w = measure(c, 'contact_cells')/16.0_dp          ! the stripe's width in cells
        call check(error, measure(c, 'contact_patch_cells'), 2.0_dp*w, "a stripe: 4 w ny/(2 ny) = 2 w", rel=1.0e-15_dp)
    end subroutine test_patch_oracle

    !> A profile (ny = 1) counts along x: 10 cells of contact (the 2-D threshold's side), and the
    !> mean length of its contact segments
    subroutine test_profile_resolution(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        character(len=*), parameter :: profile = "&grid nx = 1024, ny = 1 / &surface k_cut = 16 /"// &
            " &solver fft_planner = 'estimate' / "
        call solve('profy', profile//"&load mean_pressure_pa = 100 /", yes, error); if (allocated(error)) return
        call solve('profn', profile//"&load mean_pressure_pa = 3e4 /", no, error); if (allocated(error)) return
        call check(error, measure(yes, 'contact_cells') < sqrt(contact_cells_min) .and. &
                   measure(no, 'contact_cells') > sqrt(contact_cells_min), "the two straddle 10 cells")
        if (allocated(error)) return
        call crossing(yes, no, 'contact-resolution', error)
    end subroutine test_profile_resolution

    !> A soft solid under a pressure near its modulus (a cosine in full contact, p_max 0.37 E*)
    !> warns; under a hundredth of it does not
    subroutine test_pressure_strain(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        call solve('straiy', cosine(0.2_dp, '1e6', '3e5'), yes, error); if (allocated(error)) return
        call solve('strain', cosine(0.2_dp, '1e8', '3e5'), no, error)
        if (allocated(error)) return
        call check(error, measure(yes, 'max_pressure_over_einf') > strain_warn .and. &
                   measure(no, 'max_pressure_over_einf') < strain_warn, "the two cases straddle 0.3")
        if (allocated(error)) return
        call check(error, measure(yes, 'max_pressure_over_e0') == measure(yes, 'max_pressure_over_einf'), &
                   "an elastic solid: E0 = Einf"); if (allocated(error)) return
        call crossing(yes, no, 'pressure-strain', error)
    end subroutine test_pressure_strain

    !> A height file whose preparation filled 30 % of the scan warns, one that filled 1 % does not
    subroutine test_filled(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        call from_file('filly', 'filled_fraction', 0.3_dp, yes, error); if (allocated(error)) return
        call from_file('filln', 'filled_fraction', 0.01_dp, no, error); if (allocated(error)) return
        call check(error, measure(yes, 'filled_fraction'), 0.3_dp, "the file's share", rel=0.0_dp)
        if (allocated(error)) return
        call crossing(yes, no, 'filled-scan', error); if (allocated(error)) return
        call check(error, filled_warn == 0.02_dp, "the documented threshold")
    end subroutine test_filled

    !> A height file whose band removed 99 % of the slope variance warns, 40 % does not
    subroutine test_band_removed(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        call from_file('bandy', 'band_slope_variance_removed', 0.99_dp, yes, error); if (allocated(error)) return
        call from_file('bandn', 'band_slope_variance_removed', 0.4_dp, no, error); if (allocated(error)) return
        call check(error, measure(yes, 'band_slope_variance_removed'), 0.99_dp, "the file's share", rel=0.0_dp)
        if (allocated(error)) return
        call crossing(yes, no, 'band-slope-removed', error); if (allocated(error)) return
        call check(error, band_removed_warn == 0.5_dp, "the documented threshold")
    end subroutine test_band_removed

    !> Solve a periodic height file (a 64^2 bisinusoid of rms slope 0.02) whose attribute `name`
    !> is `share`
    subroutine from_file(tag, name, share, c, error)
        character(len=*), intent(in) :: tag, name
        real(dp), intent(in) :: share
        type(case_t), intent(out) :: c
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        real(dp) :: h(64, 64)
        character(len=:), allocatable :: h5
        integer :: i, j
        h = reshape([((1.0e-5_dp*cos(2*pi*4*i/64.0_dp)*cos(2*pi*4*j/64.0_dp), i = 0, 63), j = 0, 63)], [64, 64])
        h5 = unique_name(tag//'.h5')
        call write_heights(h5, h, 0.01_dp, error)
        if (.not. allocated(error)) call f%open(h5, 'rw', error)
        if (.not. allocated(error)) call f%writeattr('/height_m', name, share, error)
        if (.not. allocated(error)) call f%close(error)
        if (.not. allocated(error)) call solve(tag, "&surface kind = 'file', file = '"//h5//"' /"// &
                                               " &solver fft_planner = 'estimate' /", c, error)
        call remove(h5)
    end subroutine from_file

    !> A viscoelastic solid sliding where it is glassy over the whole band (tan delta ~ 1e-5)
    !> warns that the model changes nothing; at the loss peak it does not
    subroutine test_loss(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        character(len=*), parameter :: visco = sound//" &material model = 'one_term' / &motion speed_m_s = "
        call solve('lossy', visco//"1e5 /", yes, error); if (allocated(error)) return
        call solve('lossn', visco//"0.13 /", no, error); if (allocated(error)) return
        call check(error, measure(yes, 'loss_tan_delta_max') < loss_warn .and. &
                   measure(no, 'loss_tan_delta_max') > loss_warn, "the two cases straddle 1e-3")
        if (allocated(error)) return
        call crossing(yes, no, 'negligible-loss', error)
    end subroutine test_loss

    !> A layer 1 m thick on a 1 cm cell is the half-space to round-off (q0 d = 628): it warns;
    !> one of 100 um changes the compliance of the long waves (q0 d = 0.063): it does not
    subroutine test_layer(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: yes, no
        call solve('layery', sound//" &material thickness_m = 1.0 /", yes, error); if (allocated(error)) return
        call solve('layern', sound//" &material thickness_m = 1e-4 /", no, error); if (allocated(error)) return
        call check(error, measure(yes, 'layer_effect') == 0.0_dp .and. measure(no, 'layer_effect') > 0.5_dp, &
                   "1 - S(q0 d): 0 and large"); if (allocated(error)) return
        call crossing(yes, no, 'layer-no-effect', error)
    end subroutine test_layer

    ! ---------------------------------------------------------------- refusals

    !> Heights in micrometres written as metres (an rms of 2 "m" over a 1 mm cell): refused
    !> before any solve, naming the file and the likely cause
    subroutine test_refuse_file(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: c
        type(error_t), allocatable :: e
        real(dp) :: h(32, 32)
        character(len=:), allocatable :: h5
        character(len=128) :: words(3)
        integer :: i, j
        h = reshape([((2.0_dp*cos(2*pi*3*i/32.0_dp)*cos(2*pi*2*j/32.0_dp), i = 0, 31), j = 0, 31)], [32, 32])
        h5 = unique_name('umasm.h5')
        call write_heights(h5, h, 1.0e-3_dp, error); if (allocated(error)) return
        call solve('umasm', "&surface kind = 'file', file = '"//h5//"' / &solver fft_planner = 'estimate' /", c, e)
        call remove(h5)
        words(1) = "&surface file '"//h5//"'"       ! (assigned one by one: a constructor with the
        words(2) = "the rms slope of its heights is"    ! path's concatenation overran with gfortran 12)
        words(3) = "heights in um or nm written as metres"
        call expect_words(e, words, error)
    end subroutine test_refuse_file

    !> An rms height in micrometres written as metres, and a cosine as steep: refused, naming the
    !> variables; rms_slope above 10 is out of the input's range
    subroutine test_refuse_generated(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: c
        type(error_t), allocatable :: e
        call solve('rmsh', "&grid nx = 64, ny = 64 / &surface k_cut = 16, rms_slope = 0, rms_height_m = 2 /"// &
                   " &solver fft_planner = 'estimate' /", c, e)
        call expect_words(e, [character(len=40) :: "&surface rms_height_m = 2", "rms slope of", "in metres?"], error)
        if (allocated(error)) return
        call solve('cosh', "&grid nx = 64, ny = 64 / &surface kind = 'cosine', amplitude_m = 0.01,"// &
                   " wavelength_m = 2.5e-3 / &solver fft_planner = 'estimate' /", c, e)
        call expect_words(e, [character(len=40) :: "&surface amplitude_m = 0.01", "wavelength_m", "rms slope of"], &
                          error)
        if (allocated(error)) return
        call solve('slope11', "&surface rms_slope = 11 /", c, e)
        call expect_words(e, [character(len=40) :: "&surface rms_slope/rms_height_m = 11", "rms_slope <= 10"], error)
    end subroutine test_refuse_generated

    !> A modulus in MPa read as Pa is below any solid's: refused with the hint, for each model's
    !> modulus and for a one-term E0 = Einf/ratio
    subroutine test_refuse_modulus(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(error_t), allocatable :: e
        call read_text('modu1', "&material young_pa = 0.5 /", cfg, e)
        call expect_words(e, [character(len=40) :: "&material young_pa = 0.5", "no solid is softer", &
                              "MPa read as Pa?"], error); if (allocated(error)) return
        call read_text('modu2', "&material model = 'one_term', einf_pa = 100, ratio = 1000 /", cfg, e)
        call expect_words(e, [character(len=40) :: "&material ratio = 1000", "E0 = einf_pa/ratio"], error)
        if (allocated(error)) return
        call read_text('modu3', "&material model = 'relaxation', e0_pa = 0.8, relax_e_pa = 3, relax_rho_s = 1 /", &
                       cfg, e)
        call expect_words(e, [character(len=40) :: "&material e0_pa = 0.8", "1 to 1e15"], error)
        if (allocated(error)) return
        call read_text('modu4', "&material young_pa = 1 / &load mean_pressure_pa = 0.1 /", cfg, e)
        call check(error, .not. allocated(e), "1 Pa refused")
    end subroutine test_refuse_modulus

    !> Moduli in MPa read as Pa under a real load: the nominal pressure above the glassy contact
    !> modulus is refused (a single load and a swept one); just below it is accepted
    subroutine test_refuse_pressure(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(error_t), allocatable :: e
        call read_text('pres1', "&material model = 'relaxation', e0_pa = 3, relax_e_pa = 300, 2000,"// &
                       " relax_rho_s = 1e-3, 1e-6 / &load mean_pressure_pa = 32e3 /", cfg, e)
        call expect_words(e, [character(len=48) :: "&load mean_pressure_pa = 3.20e+04 Pa exceeds", &
                              "Einf/(1 - nu^2) = 3071 Pa", "MPa read as Pa?"], error); if (allocated(error)) return
        call read_text('pres2', "&material young_pa = 1e4, poisson = 0 / &sweep pressures_pa = 1e3, 2e4 /", cfg, e)
        call expect_words(e, [character(len=48) :: "&sweep pressures_pa up to 2.00e+04 Pa exceed"], error)
        if (allocated(error)) return
        call read_text('pres3', "&material young_pa = 1e4, poisson = 0 / &load mean_pressure_pa = 9.9e3 /", cfg, e)
        call check(error, .not. allocated(e), "a pressure below the modulus refused")
    end subroutine test_refuse_pressure

    ! ---------------------------------------------------------------- no-op inputs

    !> Generator settings given with kind = 'file' change nothing: one warning naming them
    subroutine test_unused_surface(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        real(dp) :: h(16, 16)
        character(len=:), allocatable :: h5
        call random_number(h); h = 1.0e-6_dp*h
        h5 = unique_name('unused.h5')
        call write_heights(h5, h, 1.0e-2_dp, error); if (allocated(error)) return
        call read_text('unused', "&surface kind = 'file', file = '"//h5//"', rms_slope = 0.1, hurst = 0.5,"// &
                       " seed = 7 /", cfg, error)
        call remove(h5)
        if (allocated(error)) return
        call check(error, size(cfg%warnings) == 1, "one warning"); if (allocated(error)) return
        call check(error, cfg%warnings(1)%code == 'unused-input' .and. index(cfg%warnings(1)%text, &
                   "&surface rms_slope, hurst, seed are not used with kind = 'file'") > 0, cfg%warnings(1)%text)
        if (allocated(error)) return
        call read_text('used', "&surface kind = 'self_affine', rms_slope = 0.1, hurst = 0.5, seed = 7 /", cfg, error)
        if (allocated(error)) return
        call check(error, size(cfg%warnings) == 0, "a random surface's own settings warn")
    end subroutine test_unused_surface

    !> Settings of another material model, and a speed on an elastic solid, change nothing
    subroutine test_unused_material(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('unusedm', "&material model = 'one_term', young_pa = 1e7, tau_s = 0.1 /", cfg, error)
        if (allocated(error)) return
        call check(error, size(cfg%warnings) == 1, "one warning"); if (allocated(error)) return
        call check(error, index(cfg%warnings(1)%text, "&material young_pa is not used with model = 'one_term'") > 0, &
                   cfg%warnings(1)%text); if (allocated(error)) return
        call read_text('unusedv', "&motion speed_m_s = 0.1 /", cfg, error); if (allocated(error)) return
        call check(error, size(cfg%warnings) == 1 .and. cfg%warnings(1)%code == 'elastic-speeds', &
                   "an elastic solid in motion"); if (allocated(error)) return
        call read_text('usedm', "&material model = 'one_term', einf_pa = 1e8, tau_s = 0.1 / &motion speed_m_s = 0.1 /", &
                       cfg, error); if (allocated(error)) return
        call check(error, size(cfg%warnings) == 0, "the model's own settings warn")
    end subroutine test_unused_material

    ! ---------------------------------------------------------------- kept with the result

    !> The case file holds /warnings (code, source, text, value, threshold; count) and /validity
    !> (each measure with its units, when it warns and its threshold), and /scalars/warnings
    subroutine test_file_warnings(error)
        type(error_t), allocatable, intent(out) :: error
        type(case_t) :: c
        type(h5file_t) :: f
        type(config_t) :: cfg
        character(len=:), allocatable :: out, warns_when
        integer(i8) :: n
        real(dp) :: x
        call read_text('fwarn', "&grid nx = 64, ny = 64 / &surface k_cut = 8 / &load mean_pressure_pa = 100 /"// &
                       " &material young_pa = 1e7, einf_pa = 2e7 / &solver fft_planner = 'estimate' /", cfg, error)
        if (allocated(error)) return
        call run_case(cfg, c, error); if (allocated(error)) return
        out = unique_name('fwarn-out.h5')
        call write_case(out, c, error); if (allocated(error)) return
        call f%open(out, 'r', error); if (allocated(error)) return
        call f%read_i0('/scalars/warnings', n, error)
        if (.not. allocated(error)) call f%read_r0('/validity/contact_cells', x, error)
        if (.not. allocated(error)) call f%read_attr_text('/validity/contact_cells', 'warns', warns_when, error)
        call f%close()
        call remove(out)
        if (allocated(error)) return
        call check(error, n == 2 .and. size(c%warnings) == 2, "an unused input and a small contact")
        if (allocated(error)) return
        call check(error, c%warnings(1)%source == 'input' .and. c%warnings(2)%source == 'validity' .and. &
                   c%warnings(2)%code == 'contact-resolution', "the input's first"); if (allocated(error)) return
        call check(error, x == measure(c, 'contact_cells') .and. warns_when == 'below', "/validity/contact_cells")
    end subroutine test_file_warnings

    !> A study keeps each case's warnings (its input's and its own) under /cases/NNNNNN/warnings,
    !> the input's at its root, and their count in /summary's column `warnings`
    subroutine test_study_warnings(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(h5file_t) :: f
        character(len=:), allocatable :: out
        character(len=64), allocatable :: columns(:)
        logical, allocatable :: is_int(:)
        integer(i8), allocatable :: rows(:, :)
        integer :: nfail, k
        out = unique_name('swarn.h5')
        call read_text('swarn', "&grid nx = 64, ny = 64 / &surface k_cut = 8 / &solver fft_planner = 'estimate' /"// &
                       " &sweep pressures_pa = 100, 3e4 / &output fields = .false. /", &
                       cfg, error)
        if (allocated(error)) return
        call run_study(cfg, out, nfail, error)
        if (.not. allocated(error)) call f%open(out, 'r', error)
        if (.not. allocated(error)) then
            call f%read_table('/summary', columns, is_int, rows, error)
            call f%close()
        end if
        call remove(out)
        if (allocated(error)) return
        k = findloc(columns, 'warnings', 1)
        call check(error, k > 0, "no column warnings"); if (allocated(error)) return
        call check(error, rows(k, 1) == 1 .and. rows(k, 2) == 0, "the light load's case warns, the other does not")
    end subroutine test_study_warnings

end module test_veslide_validity
